// The compute rasteriser's shared half (render/context.h Raster::Compute): the push constants,
// the buffers, and the set-up and coverage of one triangle as the graphics pipeline does them
// (Vulkan's rasterisation rules, with the choices lavapipe and NVIDIA make where the rules leave
// one):
//   vertex    clip = clip_from_world · (p, 1), as normal.vert;
//   clipping  against the near and far planes (0 ≤ z ≤ w) and a guard band (|x|, |y| ≤ G·w);
//   snapping  window coordinates to 1/256 pixel (GLINT_RASTER_SUBPIXEL_BITS);
//   facing    a triangle is front-facing when its signed framebuffer area is positive in
//             Vulkan's sense (VK_FRONT_FACE_COUNTER_CLOCKWISE, render/detail/vk_pipeline.cpp);
//   coverage  one sample at the sub-sample's centre, integer edge functions, the top-left rule;
//   depth     window z interpolated linearly in screen space, test LESS against the clear value
//             1.0; the visibility buffer keeps min(depth bits << 32 | triangle), so of equal
//             depths the lower triangle index wins, as in-order drawing with LESS keeps the first.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "bindings.h"

layout(push_constant) uniform RasterParams {
    mat4 clip_from_world;
    vec4 depth_row;  // linear depth = dot(depth_row.xyz, p) + depth_row.w (normal.vert)
    uvec4 size;      // width, height (sub-samples), triangle count, GLINT_RASTER_* flags
} R;

layout(std430, set = 0, binding = GLINT_RASTER_BINDING_POSITIONS) readonly buffer Positions { float positions[]; };
layout(std430, set = 0, binding = GLINT_RASTER_BINDING_INDICES) readonly buffer Indices { uint indices[]; };
layout(std430, set = 0, binding = GLINT_RASTER_BINDING_VISIBILITY) buffer Visibility { uint64_t visibility[]; };
// The large-triangle list: the indirect dispatch of raster_large.comp (x = min(count, groups),
// GLINT_RASTER_LARGE_SPLIT, 1), the count, then the triangles.
layout(std430, set = 0, binding = GLINT_RASTER_BINDING_LARGE) buffer Large {
    uint large_dispatch[3];
    uint large_count;
    uint large[];
};

const uint64_t kEmpty = 0xFFFFFFFFFFFFFFFFul;  // the cleared visibility: no triangle
const uint kLargeGroups = 4096u;               // raster_large.comp's workgroups along x, at most

vec3 position_of(uint v) { return vec3(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]); }

vec4 clip_of(vec3 p) { return R.clip_from_world * vec4(p, 1.0); }

// One (sub-)triangle ready for coverage: fixed-point window positions ordered so that the
// doubled area is positive, their window depths, its facing, and the pixel centres its
// bounding box holds.
struct Edges {
    ivec2 v0, v1, v2;
    float z0, z1, z2;
    int64_t area;  // doubled, in (1/256 px)², > 0 after set-up
    bool front;    // Vulkan's area (the negated shoelace sum) is positive
    ivec2 lo;      // first pixel (inclusive)
    ivec2 count;   // pixels along x and y (0: none)
};

ivec2 snap(vec4 c, out float z) {
    const float x_ndc = c.x / c.w;
    const float y_ndc = c.y / c.w;
    z = c.z / c.w;
    const float scale = float(1 << GLINT_RASTER_SUBPIXEL_BITS);
    const float xf = (x_ndc * 0.5 + 0.5) * float(R.size.x);
    const float yf = (y_ndc * 0.5 + 0.5) * float(R.size.y);
    return ivec2(int(roundEven(xf * scale)), int(roundEven(yf * scale)));
}

// (b − a) × (p − a): positive on the inside of edge a → b of a positive-area triangle.
int64_t edge(ivec2 a, ivec2 b, ivec2 p) {
    return int64_t(b.x - a.x) * int64_t(p.y - a.y) - int64_t(b.y - a.y) * int64_t(p.x - a.x);
}

// Whether edge a → b of a positive-area triangle owns the samples exactly on it (top-left
// rule, framebuffer y down): a top edge (horizontal, the inside below it) or a left edge.
bool top_left(ivec2 a, ivec2 b) {
    const ivec2 d = b - a;
    return d.y < 0 || (d.y == 0 && d.x > 0);
}

// Set-up of a triangle whose clip positions all lie inside the clip volume and the guard
// band; false when its box holds no pixel centre or its area is zero.
bool setup(vec4 c0, vec4 c1, vec4 c2, out Edges e) {
    e.v0 = snap(c0, e.z0);
    e.v1 = snap(c1, e.z1);
    e.v2 = snap(c2, e.z2);
    // The doubled shoelace sum Σ x_i y_(i+1) − x_(i+1) y_i; Vulkan's signed area is minus half
    // of it, and with VK_FRONT_FACE_COUNTER_CLOCKWISE a positive one is a front face.
    e.area = edge(e.v0, e.v1, e.v2);
    e.front = e.area < 0l;
    e.lo = ivec2(0);
    e.count = ivec2(0);
    if (e.area == 0l) return false;
    if (e.area < 0l) {  // order the corners so that the inside is where every edge is ≥ 0
        const ivec2 v = e.v1;
        e.v1 = e.v2;
        e.v2 = v;
        const float z = e.z1;
        e.z1 = e.z2;
        e.z2 = z;
        e.area = -e.area;
    }
    const ivec2 mn = min(min(e.v0, e.v1), e.v2);
    const ivec2 mx = max(max(e.v0, e.v1), e.v2);
    const int half_px = 1 << (GLINT_RASTER_SUBPIXEL_BITS - 1);
    const int px_mask = (1 << GLINT_RASTER_SUBPIXEL_BITS) - 1;
    // Pixel centres i·256 + 128 inside [mn, mx]: ceil((mn − 128) / 256) … floor((mx − 128) / 256)
    // (arithmetic shifts floor negative values).
    const ivec2 first = max((mn - half_px + px_mask) >> GLINT_RASTER_SUBPIXEL_BITS, ivec2(0));
    const ivec2 last = min((mx - half_px) >> GLINT_RASTER_SUBPIXEL_BITS, ivec2(R.size.xy) - 1);
    if (any(lessThan(last, first))) return false;
    e.lo = first;
    e.count = last - first + 1;
    return true;
}

// Whether the sample at pixel p's centre is covered, and its window depth there.
bool covers(Edges e, ivec2 p, out float z) {
    const int scale = 1 << GLINT_RASTER_SUBPIXEL_BITS;
    const ivec2 s = p * scale + (scale >> 1);
    const int64_t w0 = edge(e.v1, e.v2, s);  // weight of v0
    const int64_t w1 = edge(e.v2, e.v0, s);
    const int64_t w2 = edge(e.v0, e.v1, s);
    z = 0.0;
    if (w0 < 0l || (w0 == 0l && !top_left(e.v1, e.v2))) return false;
    if (w1 < 0l || (w1 == 0l && !top_left(e.v2, e.v0))) return false;
    if (w2 < 0l || (w2 == 0l && !top_left(e.v0, e.v1))) return false;
    const float a = float(e.area);
    z = (float(w0) / a) * e.z0 + (float(w1) / a) * e.z1 + (float(w2) / a) * e.z2;
    return true;
}

// Depth test and write of one covered sample of triangle t.
void write_sample(ivec2 p, float z, uint t) {
    if (!(z < 1.0)) return;  // LESS against the cleared depth 1.0
    const float zc = z > 0.0 ? z : 0.0;  // also maps −0.0 to +0.0 (its bits would sort last)
    const uint64_t key = (uint64_t(floatBitsToUint(zc)) << 32) | uint64_t(t);
    atomicMin(visibility[uint(p.y) * R.size.x + uint(p.x)], key);
}

// Samples first, first + stride, … of a set-up triangle's box (row-major).
void cover(Edges e, uint t, uint first, uint stride) {
    const uint total = uint(e.count.x) * uint(e.count.y);
    for (uint i = first; i < total; i += stride) {
        const ivec2 p = e.lo + ivec2(int(i % uint(e.count.x)), int(i / uint(e.count.x)));
        float z;
        if (covers(e, p, z)) write_sample(p, z, t);
    }
}

// The six clip planes' distances (≥ 0 inside): near z ≥ 0, far z ≤ w, the guard band.
float plane_distance(vec4 c, int k) {
    const float g = float(GLINT_RASTER_GUARD) * c.w;
    if (k == 0) return c.z;
    if (k == 1) return c.w - c.z;
    if (k == 2) return g - c.x;
    if (k == 3) return g + c.x;
    if (k == 4) return g - c.y;
    return g + c.y;
}

bool inside_all(vec4 c) {
    for (int k = 0; k < 6; ++k) {
        if (!(plane_distance(c, k) >= 0.0)) return false;
    }
    return c.w > 0.0;
}

void push_large(uint t) {
    const uint slot = atomicAdd(large_count, 1u);
    large[slot] = t;
    atomicMax(large_dispatch[0], min(slot + 1u, kLargeGroups));
}

// Rasterises triangle t: samples first, first + stride, … of each covered (sub-)triangle's box.
// The small pass (stride 1) hands a triangle with more than GLINT_RASTER_SMALL_PIXELS pixel
// centres in its box, or one that needs clipping, to the large pass instead.
void raster(uint t, bool large_pass, uint first, uint stride) {
    const vec4 c0 = clip_of(position_of(indices[3 * t]));
    const vec4 c1 = clip_of(position_of(indices[3 * t + 1]));
    const vec4 c2 = clip_of(position_of(indices[3 * t + 2]));
    const bool cull = (R.size.w & GLINT_RASTER_CULL) != 0u;
    if (inside_all(c0) && inside_all(c1) && inside_all(c2)) {
        Edges e;
        if (!setup(c0, c1, c2, e)) return;
        if (cull && !e.front) return;
        if (!large_pass && uint(e.count.x) * uint(e.count.y) > GLINT_RASTER_SMALL_PIXELS) {
            push_large(t);
            return;
        }
        cover(e, t, first, stride);
        return;
    }
    // Wholly outside one plane: nothing to draw.
    for (int k = 0; k < 6; ++k) {
        if (plane_distance(c0, k) < 0.0 && plane_distance(c1, k) < 0.0 &&
            plane_distance(c2, k) < 0.0)
            return;
    }
    if (cull) {
        // The sign of the homogeneous determinant of the (x, y, w) rows is that of the visible
        // part's shoelace sum (the clipped corners are positive combinations of the corners).
        const dvec3 a = dvec3(c0.xyw), b = dvec3(c1.xyw), c = dvec3(c2.xyw);
        if (!(dot(a, cross(b, c)) < 0.0lf)) return;
    }
    if (!large_pass) {
        push_large(t);
        return;
    }
    // Sutherland–Hodgman in clip space: each plane adds at most one corner.
    vec4 poly[9];
    poly[0] = c0;
    poly[1] = c1;
    poly[2] = c2;
    int n = 3;
    for (int k = 0; k < 6; ++k) {
        vec4 kept[9];
        int m = 0;
        for (int i = 0; i < n; ++i) {
            const vec4 a = poly[i];
            const vec4 b = poly[(i + 1) % n];
            const float da = plane_distance(a, k);
            const float db = plane_distance(b, k);
            if (da >= 0.0) kept[m++] = a;
            if ((da >= 0.0) != (db >= 0.0)) kept[m++] = mix(a, b, da / (da - db));
        }
        n = m;
        poly = kept;
        if (n < 3) return;
    }
    for (int i = 1; i + 1 < n; ++i) {
        if (!(poly[0].w > 0.0 && poly[i].w > 0.0 && poly[i + 1].w > 0.0)) continue;
        Edges e;
        if (setup(poly[0], poly[i], poly[i + 1], e)) cover(e, t, first, stride);
    }
}
