#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// The GPU atlas's vertex pass (render/gpu_atlas.h), one invocation per reference vertex, after
// the pixel pass of the same view:
//   gather  a vertex that no pixel centre fell on reads the pixel it projects to
//           (scanner/backproject.cpp gather);
//   fold    this view's maximum and most frontal observation into the sweep's: the first view
//           keeps a tie, as AtlasAccumulator::observe does view after view; then the scratch
//           is cleared for the next view.
// Only this invocation touches vertex v in this pass, so the fold needs no atomics.
#include "atlas_common.glsl"

layout(local_size_x = GLINT_ATLAS_VERTEX_GROUP) in;

// scanner/backproject.cpp gather() for vertex v: true and the observation when it has one.
bool gather(uint v, out uint pixel, out float cos_f) {
    pixel = 0u;
    cos_f = 0.0;
    const dvec3 p = position_of(v);
    // Projector::operator(): camera frame, then pixel coordinates and depth.
    const dvec3 c = transform_point(P.camera_from_world[0], P.camera_from_world[1], P.camera_from_world[2], p);
    precise double depth = -c.z;
    const bool perspective = (P.mode.x & GLINT_ATLAS_PERSPECTIVE) != 0u;
    const double scale = perspective ? depth : 1.0lf;
    precise double x_ndc = c.x / (P.projector.x * scale);
    precise double y_ndc = c.y / (P.projector.y * scale);
    precise double u = (0.5lf * (x_ndc + 1.0lf)) * P.frame.x;
    precise double w = (0.5lf * (1.0lf - y_ndc)) * P.frame.y;
    if (!(u >= 0.0lf && w >= 0.0lf && u < P.frame.x && w < P.frame.y)) return false;
    pixel = uint(w) * P.size.x + uint(u);
    const PixelDeviation d = pixels[pixel];
    if ((d.flags & GLINT_PIXEL_REFERENCE_COVERED) == 0u) return false;
    precise double off = double(d.reference_depth) - depth;
    if (abs(off) > P.projector.z) return false;
    dvec3 to_camera = P.to_ortho_camera.xyz;
    if (perspective) {
        precise dvec3 e = P.eye.xyz - p;
        to_camera = normalized3(e);
    }
    const double cos_inc = dot3(normal_of(v), to_camera);
    if (cos_inc < P.projector.w) return false;
    const bool missing = (d.flags & GLINT_PIXEL_SILHOUETTE_MASK) == GLINT_PIXEL_REFERENCE_ONLY;
    if (!missing && (d.flags & GLINT_PIXEL_COMPARED) == 0u) return false;  // not a sample
    cos_f = float(cos_inc);
    return true;
}

void main() {
    const uint v = gl_GlobalInvocationID.x;
    if (v >= vertex_count()) return;
    if (scratch_cos[v] == 0u) {
        uint pixel;
        float cos_f;
        if (gather(v, pixel, cos_f)) {
            const PixelDeviation d = pixels[pixel];
            const bool missing = (d.flags & GLINT_PIXEL_SILHOUETTE_MASK) == GLINT_PIXEL_REFERENCE_ONLY;
            observe(v, 1.0, true, true, missing, d.value, d.signed_depth, cos_f, pixel);
        }
    }
    const uint best = scratch_cos[v];
    if (best > 1u) {  // observed in this view (1: scattered only)
        const uint at = word_index(GLINT_WORD_BEST_COS, v);
        if (uintBitsToFloat(best) > uintBitsToFloat(words[at])) {
            words[at] = best;
            words[word_index(GLINT_WORD_BEST_VIEW, v)] = uint(P.view.x);
        }
    }
    const uint64_t key = scratch_key[v];
    if (key != 0ul) {  // a nearest valid observation in this view
        const float value = uintBitsToFloat(uint(key >> 32));
        const uint pixel = ~uint(key & 0xFFFFFFFFul);
        const uint view_at = word_index(GLINT_WORD_MAX_VIEW, v);
        const uint max_at = word_index(GLINT_WORD_MAX, v);
        if (int(words[view_at]) < 0 || value > uintBitsToFloat(words[max_at])) {
            words[max_at] = floatBitsToUint(value);
            words[word_index(GLINT_WORD_DEPTH_AT_MAX, v)] = floatBitsToUint(pixels[pixel].signed_depth);
            words[view_at] = uint(P.view.x);
        }
    }
    scratch_cos[v] = 0u;
    scratch_key[v] = 0ul;
}
