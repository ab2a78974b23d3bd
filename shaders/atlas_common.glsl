// The GPU atlas's declarations and arithmetic shared by its two passes (render/gpu_atlas.h).
//
// Every computation mirrors the CPU path's operations in their order and precision, so that on
// an IEEE device the results equal the CPU's: float where the CPU uses float (resolve, normal
// comparison), double where it uses double (rays, barycentrics, projection, acos). `precise`
// forbids fused multiply-adds (the CPU build uses none). Float division and square root go
// through double and back, which rounds them correctly (53 ≥ 2·24 + 2 bits), as the CPU's are.
// Vector expressions follow Eigen's association (checked against Eigen 3.4): dot products and
// isometries sum ((x + y) + z) + t; a 3×3 matrix times a vector sums rows 0 and 1 as
// (x + y) + z and row 2 as x + (y + z).
#include "bindings.h"

// Mirrored by render/detail/gpu_atlas_layout.h (std140; offsets checked there).
layout(std140, set = 0, binding = GLINT_ATLAS_BINDING_PARAMS) uniform AtlasParams {
    dvec4 world_from_camera[3];  // rows (R_r0, R_r1, R_r2, t_r)
    dvec4 camera_from_world[3];  // rows, the inverse isometry
    dvec4 eye;                   // xyz: camera centre
    dvec4 to_ortho_camera;       // xyz: −forward, the direction to an orthographic camera
    dvec4 frame;                 // width, height, aspect = width / height, ortho_half_height
    dvec4 projector;             // half_width, half_height, depth_tolerance, min_cos_incidence
    dvec4 scales;                // fixed-point scales: weight, value, depth, angle
    dvec4 camera;                // tan(fov_y / 2), 0, 0, 0
    uvec4 size;                  // width, height, supersample, vertex_count
    uvec4 mode;                  // GLINT_ATLAS_* flags, sums base, words base, 0
    ivec4 view;                  // view index, 0, 0, 0
    vec4 thresholds;             // 1/s², min_coverage, frame mask threshold (0: none), missing_value
    vec4 rgb;                    // 1/255 as OpenImageIO converts 8-bit values, 0, 0, 0
} P;

layout(set = 0, binding = GLINT_ATLAS_BINDING_REF_NORMAL_DEPTH, rgba32f) uniform readonly image2D ref_normal_depth;
layout(set = 0, binding = GLINT_ATLAS_BINDING_REF_PRIMITIVE, r32ui) uniform readonly uimage2D ref_primitive;
layout(set = 0, binding = GLINT_ATLAS_BINDING_EXA_NORMAL_DEPTH, rgba32f) uniform readonly image2D exa_normal_depth;
layout(set = 0, binding = GLINT_ATLAS_BINDING_EXA_PRIMITIVE, r32ui) uniform readonly uimage2D exa_primitive;

layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_POSITIONS) readonly buffer Positions { float positions[]; };
layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_NORMALS) readonly buffer Normals { float normals[]; };
layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_INDICES) readonly buffer Indices { uint indices[]; };
layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_SUMS) buffer Sums { int64_t sums[]; };
layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_WORDS) buffer Words { uint words[]; };
layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_SCRATCH_KEY) buffer ScratchKey { uint64_t scratch_key[]; };
layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_SCRATCH_COS) buffer ScratchCos { uint scratch_cos[]; };

struct PixelDeviation {
    float value;            // the metric (valid where flags has GLINT_PIXEL_COMPARED)
    float signed_depth;     // reference − examined depth; NaN bits where not compared
    float reference_depth;  // the resolved reference depth
    uint flags;             // GLINT_PIXEL_*
};
layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_PIXELS) buffer Pixels { PixelDeviation pixels[]; };

layout(std430, set = 0, binding = GLINT_ATLAS_BINDING_SUMMARY) buffer Summary {
    uint reference_pixels;
    uint compared;
    uint reference_only;
    uint examined_only;
    uint max_angle_bits;
    uint unused;
    int64_t angle_sum;  // fixed point, P.scales.w
} summary;

const uint kNoPrimitive = GLINT_NO_PRIMITIVE;
const uint kNaNBits = 0x7FC00000u;
const double kPi = 3.141592653589793lf;

uint vertex_count() { return P.size.w; }

dvec3 position_of(uint v) {
    return dvec3(double(positions[3 * v]), double(positions[3 * v + 1]), double(positions[3 * v + 2]));
}

dvec3 normal_of(uint v) {
    return dvec3(double(normals[3 * v]), double(normals[3 * v + 1]), double(normals[3 * v + 2]));
}

double dot3(dvec3 a, dvec3 b) {
    precise double d = (a.x * b.x + a.y * b.y) + a.z * b.z;
    return d;
}

dvec3 cross3(dvec3 a, dvec3 b) {
    precise dvec3 c = dvec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
    return c;
}

// Isometry (rows r) applied to a point: t + R·p (Eigen's Transform * vector).
dvec3 transform_point(dvec4 r0, dvec4 r1, dvec4 r2, dvec3 p) {
    precise double x = r0.w + ((r0.x * p.x + r0.y * p.y) + r0.z * p.z);
    precise double y = r1.w + ((r1.x * p.x + r1.y * p.y) + r1.z * p.z);
    precise double z = r2.w + ((r2.x * p.x + r2.y * p.y) + r2.z * p.z);
    return dvec3(x, y, z);
}

// The rotation alone times a vector (Eigen's Matrix3d * Vector3d: row 2 sums the other way).
dvec3 rotate(dvec4 r0, dvec4 r1, dvec4 r2, dvec3 d) {
    precise double x = (r0.x * d.x + r0.y * d.y) + r0.z * d.z;
    precise double y = (r1.x * d.x + r1.y * d.y) + r1.z * d.z;
    precise double z = r2.x * d.x + (r2.y * d.y + r2.z * d.z);
    return dvec3(x, y, z);
}

// Eigen's normalized(): each component divided by the norm.
dvec3 normalized3(dvec3 a) {
    precise double n2 = dot3(a, a);
    if (!(n2 > 0.0lf)) return a;
    precise double n = sqrt(n2);
    precise dvec3 r = dvec3(a.x / n, a.y / n, a.z / n);
    return r;
}

// Correctly rounded float square root and quotient (through double).
float sqrt_f(float x) { return float(sqrt(double(x))); }
float div_f(float a, float b) { return float(double(a) / double(b)); }

// asin(x) for |x| ≤ 0.5: its Taylor series, x · Σ a_n x^(2n), a_n = (2n)! / (4^n (n!)² (2n + 1));
// 26 terms leave a remainder below 1e-18 of the result.
double asin_series(double x) {
    const double a[26] = double[](
        1.0lf, 0.16666666666666666lf, 0.075lf, 0.044642857142857144lf, 0.030381944444444444lf,
        0.022372159090909092lf, 0.017352764423076924lf, 0.01396484375lf, 0.011551800896139705lf,
        0.009761609529194078lf, 0.008390335809616815lf, 0.0073125258735988454lf, 0.006447210311889649lf,
        0.005740037670841924lf, 0.005153309682319905lf, 0.004660143486915096lf, 0.004240907093679363lf,
        0.003880964558837669lf, 0.0035692053938259347lf, 0.003297059503473485lf, 0.0030578216492580306lf,
        0.002846178401108942lf, 0.00265787063820729lf, 0.0024894486782468836lf, 0.002338091892111975lf,
        0.0022014739737101384lf);
    precise double x2 = x * x;
    precise double p = a[25];
    for (int n = 24; n >= 0; --n) p = p * x2 + a[n];
    precise double r = x * p;
    return r;
}

// acos in double from the series: |c| ≤ 1/2 directly, else through the half angle, whose sine
// sqrt((1 ∓ c) / 2) is at most 1/2 (1 ∓ c is exact there).
double acos_d(double c) {
    if (c > 0.5lf) {
        precise double h = sqrt((1.0lf - c) * 0.5lf);
        precise double r = 2.0lf * asin_series(h);
        return r;
    }
    if (c < -0.5lf) {
        precise double h = sqrt((1.0lf + c) * 0.5lf);
        precise double r = kPi - 2.0lf * asin_series(h);
        return r;
    }
    precise double r = kPi * 0.5lf - asin_series(c);
    return r;
}

// A value in the sums' fixed point (scale a power of two; the caller keeps it in range).
int64_t to_fixed(double x, double scale) {
    precise double y = x * scale;
    return int64_t(roundEven(y));
}

uint sum_index(uint field, uint v) { return P.mode.y + field * vertex_count() + v; }
uint word_index(uint field, uint v) { return P.mode.z + field * vertex_count() + v; }

// One observation of vertex v (AtlasAccumulator::observe): counts and sums now, the maximum
// and the most frontal incidence into this view's scratch (folded by atlas_vertices.comp).
void observe(uint v, float w, bool nearest, bool valid, bool missing, float value, float signed_depth,
             float cos_incidence, uint pixel) {
    atomicAdd(words[word_index(GLINT_WORD_COUNT, v)], 1u);
    atomicMax(scratch_cos[v], floatBitsToUint(cos_incidence));  // > 0: ordered as uint
    if (!valid) return;
    precise double wd = double(w);
    atomicAdd(sums[sum_index(GLINT_SUM_WEIGHT, v)], to_fixed(wd, P.scales.x));
    precise double wv = wd * double(value);
    atomicAdd(sums[sum_index(GLINT_SUM_VALUE, v)], to_fixed(wv, P.scales.y));
    if (missing) {
        atomicAdd(sums[sum_index(GLINT_SUM_MISSING, v)], to_fixed(wd, P.scales.x));
    } else {
        // A compared pixel's signed depth is finite; a missing one's is NaN (no depth sum).
        precise double wz = wd * double(signed_depth);
        atomicAdd(sums[sum_index(GLINT_SUM_DEPTH, v)], to_fixed(wz, P.scales.z));
    }
    if (nearest) {
        // value ≥ 0: its bits order as the value; ties go to the first pixel in row-major order.
        const uint64_t key = (uint64_t(floatBitsToUint(value)) << 32) | uint64_t(~pixel);
        atomicMax(scratch_key[v], key);
    }
}
