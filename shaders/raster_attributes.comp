#version 450
#extension GL_GOOGLE_include_directive : require
// The compute rasteriser's attribute pass (shaders/raster_common.glsl), one invocation per
// sub-sample: what normal.frag writes for the triangle the visibility buffer kept there — the
// vertex normals and the linear depth (normal.vert's outputs) interpolated perspective-correctly
// at the sample's centre, the normal renormalised — or the clear values where none was kept.
#include "raster_common.glsl"

layout(local_size_x = GLINT_RASTER_TILE, local_size_y = GLINT_RASTER_TILE) in;

layout(std430, set = 0, binding = GLINT_RASTER_BINDING_NORMALS) readonly buffer Normals { float normals[]; };
layout(set = 0, binding = GLINT_RASTER_BINDING_NORMAL_DEPTH, rgba32f) uniform writeonly image2D out_normal_depth;
layout(set = 0, binding = GLINT_RASTER_BINDING_PRIMITIVE, r32ui) uniform writeonly uimage2D out_primitive;

vec3 normal_of(uint v) { return vec3(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]); }

void main() {
    const ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (q.x >= int(R.size.x) || q.y >= int(R.size.y)) return;
    const uint64_t key = visibility[uint(q.y) * R.size.x + uint(q.x)];
    if (key == kEmpty) {  // the render pass's clear values
        imageStore(out_normal_depth, q, vec4(0.0));
        imageStore(out_primitive, q, uvec4(GLINT_NO_PRIMITIVE));
        return;
    }
    const uint t = uint(key & 0xFFFFFFFFul);
    const uint i0 = indices[3 * t], i1 = indices[3 * t + 1], i2 = indices[3 * t + 2];
    const vec3 p0 = position_of(i0), p1 = position_of(i1), p2 = position_of(i2);
    const vec4 c0 = clip_of(p0), c1 = clip_of(p1), c2 = clip_of(p2);
    // Perspective-correct weights at the sample: λ ∝ adj(C)·s, C the (x, y, w) columns of the
    // corners in clip space, s the sample in normalised device coordinates (x, y, 1); exact
    // for any w, so clipped triangles need no special case.
    const dvec3 s = dvec3((2.0lf * (double(q.x) + 0.5lf)) / double(R.size.x) - 1.0lf,
                          (2.0lf * (double(q.y) + 0.5lf)) / double(R.size.y) - 1.0lf, 1.0lf);
    const dvec3 a = dvec3(c0.xyw), b = dvec3(c1.xyw), c = dvec3(c2.xyw);
    double l0 = dot(s, cross(b, c));
    double l1 = dot(s, cross(c, a));
    double l2 = dot(s, cross(a, b));
    const double sum = l0 + l1 + l2;
    if (sum != 0.0lf) {
        l0 /= sum;
        l1 /= sum;
        l2 /= sum;
    } else {  // degenerate in clip space: only an edge-on sliver; any corner's values do
        l0 = 1.0lf;
        l1 = 0.0lf;
        l2 = 0.0lf;
    }
    const vec3 n = vec3(l0 * dvec3(normal_of(i0)) + l1 * dvec3(normal_of(i1)) + l2 * dvec3(normal_of(i2)));
    const float d0 = dot(R.depth_row.xyz, p0) + R.depth_row.w;
    const float d1 = dot(R.depth_row.xyz, p1) + R.depth_row.w;
    const float d2 = dot(R.depth_row.xyz, p2) + R.depth_row.w;
    const float depth = float(l0 * double(d0) + l1 * double(d1) + l2 * double(d2));
    // normal.frag: a zero interpolated normal stays zero.
    const float len = length(n);
    imageStore(out_normal_depth, q, vec4(len > 0.0 ? n / len : vec3(0.0), depth));
    imageStore(out_primitive, q, uvec4(t));
}
