#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// The GPU atlas's pixel pass (render/gpu_atlas.h), one invocation per output pixel:
//   resolve   both frames' s×s sub-samples (render/detail/resolve.cpp, then the renderer's
//             coverage mask: render/renderer.cpp finish_frame);
//   compare   silhouette, angle, signed depth and the metric (scanner/compare.cpp, metric.cpp);
//   scatter   the pixel's sample onto its reference triangle (scanner/backproject.cpp scatter,
//             scanner/atlas.cpp add);
//   summary   the view's numbers, reduced per workgroup, one atomic each per workgroup.
#include "atlas_common.glsl"

layout(local_size_x = GLINT_ATLAS_TILE, local_size_y = GLINT_ATLAS_TILE) in;

shared uint s_counts[4];  // reference pixels, compared, reference only, examined only
shared uint s_max_angle;  // float bits
shared int64_t s_angle_sum[GLINT_ATLAS_TILE * GLINT_ATLAS_TILE];

struct Resolved {
    vec3 normal;
    uint primitive;
    float depth;
    float coverage;
};

Resolved uncovered() { return Resolved(vec3(0.0), kNoPrimitive, uintBitsToFloat(0x7F800000u), 0.0); }

uint primitive_at(bool reference, ivec2 q) {
    return reference ? imageLoad(ref_primitive, q).r : imageLoad(exa_primitive, q).r;
}

vec4 normal_depth_at(bool reference, ivec2 q) {
    return reference ? imageLoad(ref_normal_depth, q) : imageLoad(exa_normal_depth, q);
}

// resolve_rows (render/detail/resolve.cpp) for one pixel, then finish_frame's coverage mask.
Resolved resolve(bool reference, ivec2 pixel) {
    const int s = int(P.size.z);
    const int centre = s / 2;
    precise float nx = 0.0, ny = 0.0, nz = 0.0, depth = 0.0;
    int covered = 0;
    uint first_id = kNoPrimitive;
    uint centre_id = kNoPrimitive;
    for (int j = 0; j < s; ++j) {
        for (int i = 0; i < s; ++i) {
            const ivec2 q = pixel * s + ivec2(i, j);
            const uint id = primitive_at(reference, q);
            if (id == kNoPrimitive) continue;
            const vec4 nd = normal_depth_at(reference, q);
            nx += nd.x;
            ny += nd.y;
            nz += nd.z;
            depth += nd.w;
            ++covered;
            if (first_id == kNoPrimitive) first_id = id;
            if (i == centre && j == centre) centre_id = id;
        }
    }
    precise float len2 = (nx * nx + ny * ny) + nz * nz;
    const float len = sqrt_f(len2);
    precise float cancel = 1e-3 * float(covered);
    if (covered == 0 || len <= cancel) return uncovered();
    const float inv = div_f(1.0, len);
    Resolved r;
    precise vec3 n = vec3(nx * inv, ny * inv, nz * inv);
    r.normal = n;
    r.primitive = centre_id != kNoPrimitive ? centre_id : first_id;
    r.depth = div_f(depth, float(covered));
    precise float coverage = float(covered) * P.thresholds.x;
    r.coverage = coverage;
    const float mask = P.thresholds.z;  // min_coverage − 1e-6 of the frame options; 0: none
    if (mask > 0.0 && r.coverage > 0.0 && r.coverage < mask) return uncovered();
    return r;
}

bool in_frame(Resolved r) { return r.primitive != kNoPrimitive && r.coverage > 0.0; }
bool fully_covered(Resolved r) { return r.primitive != kNoPrimitive && r.coverage >= P.thresholds.y; }

// The paper's 8-bit colour channel: lround(clamp(0.5·n + 0.5, 0, 1) · 255).
float paper_channel(float n) {
    precise float t = 0.5 * n + 0.5;
    precise float x = clamp(t, 0.0, 1.0) * 255.0;
    const float f = floor(x);
    precise float frac = x - f;
    return frac >= 0.5 ? f + 1.0 : f;
}

// The RGB metric (scanner/metric.cpp rgb_values): |Δ| of each 8-bit channel as OpenImageIO
// hands it back (k · (1/255)), then 255 · (r + g + b) / 3.
float rgb_value(vec3 a, vec3 b) {
    precise float dr = abs(paper_channel(a.x) - paper_channel(b.x)) * P.rgb.x;
    precise float dg = abs(paper_channel(a.y) - paper_channel(b.y)) * P.rgb.x;
    precise float db = abs(paper_channel(a.z) - paper_channel(b.z)) * P.rgb.x;
    precise float sum = 255.0 * ((dr + dg) + db);
    return div_f(sum, 3.0);
}

// The angle between two normals in degrees, as compare_frames computes it.
bool angle_between(vec3 a, vec3 b, out float angle) {
    precise float d = (a.x * b.x + a.y * b.y) + a.z * b.z;
    precise float aa = (a.x * a.x + a.y * a.y) + a.z * a.z;
    precise float bb = (b.x * b.x + b.y * b.y) + b.z * b.z;
    const double na = double(sqrt_f(aa));
    const double nb = double(sqrt_f(bb));
    angle = 0.0;
    if (!(na > 0.0lf && nb > 0.0lf)) return false;
    precise double nn = na * nb;
    precise double c = clamp(double(d) / nn, -1.0lf, 1.0lf);
    precise double deg = (acos_d(c) * 180.0lf) / kPi;
    angle = float(deg);
    return true;
}

// Camera::pixel_ray through image point (u, v).
void pixel_ray(double u, double v, out dvec3 origin, out dvec3 direction) {
    precise double x_ndc = (2.0lf * u) / P.frame.x - 1.0lf;
    precise double y_ndc = 1.0lf - (2.0lf * v) / P.frame.y;
    const double aspect = P.frame.z;
    dvec3 origin_cam;
    dvec3 dir_cam;
    if ((P.mode.x & GLINT_ATLAS_PERSPECTIVE) == 0u) {
        const double h = P.frame.w;
        precise double ox = (x_ndc * h) * aspect;
        precise double oy = y_ndc * h;
        origin_cam = dvec3(ox, oy, 0.0lf);
        dir_cam = dvec3(0.0lf, 0.0lf, -1.0lf);
    } else {
        const double t = P.camera.x;
        precise double dx = (x_ndc * t) * aspect;
        precise double dy = y_ndc * t;
        origin_cam = dvec3(0.0lf);
        dir_cam = normalized3(dvec3(dx, dy, -1.0lf));
    }
    origin = transform_point(P.world_from_camera[0], P.world_from_camera[1], P.world_from_camera[2], origin_cam);
    direction = rotate(P.world_from_camera[0], P.world_from_camera[1], P.world_from_camera[2], dir_cam);
}

// scanner/backproject.cpp barycentric(): where the ray meets triangle t's plane, clamped to
// the triangle, and the signed incidence.
bool barycentric(uint t, dvec3 origin, dvec3 dir, out vec3 w, out double cos_incidence) {
    w = vec3(0.0);
    cos_incidence = 0.0lf;
    const dvec3 a = position_of(indices[3 * t]);
    const dvec3 b = position_of(indices[3 * t + 1]);
    const dvec3 c = position_of(indices[3 * t + 2]);
    precise dvec3 ab = b - a;
    precise dvec3 ac = c - a;
    const dvec3 n = cross3(ab, ac);
    precise double area2 = sqrt(dot3(n, n));
    if (!(area2 > 0.0lf)) return false;
    const double denom = dot3(n, dir);
    precise double ci = -denom / area2;
    cos_incidence = ci;
    precise double degenerate = 1e-12lf * area2;
    if (abs(denom) < degenerate) return false;
    precise dvec3 ao = a - origin;
    precise double s = dot3(n, ao) / denom;
    precise dvec3 p = origin + s * dir;
    precise double area4 = area2 * area2;
    precise dvec3 bp = b - p;
    precise dvec3 cp = c - p;
    precise dvec3 ap = a - p;
    precise double ua = dot3(n, cross3(bp, cp)) / area4;
    precise double ub = dot3(n, cross3(cp, ap)) / area4;
    precise double wa = max(0.0lf, ua);
    precise double wb = max(0.0lf, ub);
    precise double wc = max(0.0lf, (1.0lf - ua) - ub);
    precise double sum = (wa + wb) + wc;
    if (!(sum > 0.0lf)) return false;
    w = vec3(float(wa / sum), float(wb / sum), float(wc / sum));
    return true;
}

// scanner/backproject.cpp scatter() for one covered reference pixel.
void scatter(uint pixel, ivec2 xy, uint triangle, bool valid, bool missing, float value, float signed_depth) {
    dvec3 origin, dir;
    pixel_ray(double(xy.x) + 0.5lf, double(xy.y) + 0.5lf, origin, dir);
    vec3 w;
    double cos_inc;
    if (!barycentric(triangle, origin, dir, w, cos_inc)) return;
    if (cos_inc < P.projector.w) return;
    const float cos_f = float(cos_inc);
    // AtlasAccumulator::add: the maximum goes to the largest weight's vertex (the first of
    // equal ones); a weight below 1e-3 is no observation.
    const int nearest = w[1] > w[0] ? (w[2] > w[1] ? 2 : 1) : (w[2] > w[0] ? 2 : 0);
    for (int k = 0; k < 3; ++k) {
        const uint v = indices[3 * triangle + uint(k)];
        if (w[k] >= 1e-3) {
            observe(v, w[k], k == nearest, valid, missing, value, signed_depth, cos_f, pixel);
        } else {
            // Scattered in this view but not observed (1: below every positive float's bits;
            // observe() leaves the incidence's bits): no gather for v in this view.
            atomicMax(scratch_cos[v], 1u);
        }
    }
}

void main() {
    const uint li = gl_LocalInvocationIndex;
    if (li == 0u) {
        s_counts[0] = 0u;
        s_counts[1] = 0u;
        s_counts[2] = 0u;
        s_counts[3] = 0u;
        s_max_angle = 0u;
    }
    memoryBarrierShared();
    barrier();

    const ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
    int64_t angle_fixed = 0l;
    if (xy.x < int(P.size.x) && xy.y < int(P.size.y)) {
        const uint pixel = uint(xy.y) * P.size.x + uint(xy.x);
        const Resolved r = resolve(true, xy);
        const Resolved e = resolve(false, xy);
        const bool ref_covered = fully_covered(r);
        uint flags = ref_covered ? GLINT_PIXEL_REFERENCE_COVERED : 0u;
        float angle = 0.0;
        bool compared = false;
        if (in_frame(r) != in_frame(e)) {
            // A pixel partly covered in one frame and empty in the other is an edge shift.
            if (in_frame(r) && ref_covered) {
                flags |= GLINT_PIXEL_REFERENCE_ONLY;
                atomicAdd(s_counts[2], 1u);
            } else if (in_frame(e) && fully_covered(e)) {
                flags |= GLINT_PIXEL_EXAMINED_ONLY;
                atomicAdd(s_counts[3], 1u);
            }
        } else if (ref_covered && fully_covered(e)) {
            compared = angle_between(r.normal, e.normal, angle);
        }
        float value = 0.0;
        float signed_depth = uintBitsToFloat(kNaNBits);
        if (compared) {
            flags |= GLINT_PIXEL_COMPARED;
            value = (P.mode.x & GLINT_ATLAS_METRIC_RGB) != 0u ? rgb_value(r.normal, e.normal) : angle;
            precise float sd = r.depth - e.depth;
            signed_depth = sd;
            atomicAdd(s_counts[1], 1u);
            atomicMax(s_max_angle, floatBitsToUint(angle));
            angle_fixed = to_fixed(double(angle), P.scales.w);
        }
        const bool missing = (flags & GLINT_PIXEL_SILHOUETTE_MASK) == GLINT_PIXEL_REFERENCE_ONLY;
        if (missing) value = P.thresholds.w;
        pixels[pixel] = PixelDeviation(value, signed_depth, r.depth, flags);
        if (ref_covered) {
            atomicAdd(s_counts[0], 1u);
            scatter(pixel, xy, r.primitive, compared || missing, missing, value, signed_depth);
        }
    }
    s_angle_sum[li] = angle_fixed;
    memoryBarrierShared();
    barrier();
    for (uint stride = (GLINT_ATLAS_TILE * GLINT_ATLAS_TILE) / 2; stride > 0u; stride >>= 1) {
        if (li < stride) s_angle_sum[li] += s_angle_sum[li + stride];
        memoryBarrierShared();
        barrier();
    }
    if (li == 0u) {
        if (s_counts[0] != 0u) atomicAdd(summary.reference_pixels, s_counts[0]);
        if (s_counts[1] != 0u) atomicAdd(summary.compared, s_counts[1]);
        if (s_counts[2] != 0u) atomicAdd(summary.reference_only, s_counts[2]);
        if (s_counts[3] != 0u) atomicAdd(summary.examined_only, s_counts[3]);
        if (s_max_angle != 0u) atomicMax(summary.max_angle_bits, s_max_angle);
        if (s_angle_sum[0] != 0l) atomicAdd(summary.angle_sum, s_angle_sum[0]);
    }
}
