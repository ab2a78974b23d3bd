// C++ mirrors of the GPU atlas's GLSL structs (shaders/atlas_common.glsl), with their sizes and
// offsets checked (STYLE.md §2: a struct mirrored on both sides gets static_asserts).
#pragma once

#include "spirv/bindings.h"

#include <cstddef>
#include <cstdint>

namespace glint::detail {

/// uniform AtlasParams (std140: dvec4 members at multiples of 32 bytes, then 16-byte vectors).
struct AtlasParams {
    double world_from_camera[12];  ///< 3 rows (R_r0, R_r1, R_r2, t_r)
    double camera_from_world[12];  ///< 3 rows of the inverse isometry
    double eye[4];                 ///< xyz
    double to_ortho_camera[4];     ///< xyz: −forward
    double frame[4];               ///< width, height, width / height, ortho_half_height
    double projector[4];           ///< half_width, half_height, depth_tolerance, min_cos_incidence
    double scales[4];              ///< fixed-point scales: weight, value, depth, angle
    double camera[4];              ///< tan(fov_y / 2), 0, 0, 0
    std::uint32_t size[4];         ///< width, height, supersample, vertex_count
    std::uint32_t mode[4];         ///< GLINT_ATLAS_* flags, sums base, words base, 0
    std::int32_t view[4];          ///< view index, 0, 0, 0
    float thresholds[4];           ///< 1/s², min_coverage, frame mask threshold, missing_value
    float rgb[4];                  ///< 1/255 as OpenImageIO scales 8-bit values, 0, 0, 0
};
static_assert(offsetof(AtlasParams, camera_from_world) == 96);
static_assert(offsetof(AtlasParams, eye) == 192);
static_assert(offsetof(AtlasParams, to_ortho_camera) == 224);
static_assert(offsetof(AtlasParams, frame) == 256);
static_assert(offsetof(AtlasParams, projector) == 288);
static_assert(offsetof(AtlasParams, scales) == 320);
static_assert(offsetof(AtlasParams, camera) == 352);
static_assert(offsetof(AtlasParams, size) == 384);
static_assert(offsetof(AtlasParams, mode) == 400);
static_assert(offsetof(AtlasParams, view) == 416);
static_assert(offsetof(AtlasParams, thresholds) == 432);
static_assert(offsetof(AtlasParams, rgb) == 448);
static_assert(sizeof(AtlasParams) == 464,
              "AtlasParams must match the std140 block in atlas_common.glsl");

/// buffer Summary (std430): one view's numbers.
struct ViewTotals {
    std::uint32_t reference_pixels;
    std::uint32_t compared;
    std::uint32_t reference_only;
    std::uint32_t examined_only;
    std::uint32_t max_angle_bits;  ///< float bits
    std::uint32_t unused;
    std::int64_t angle_sum;  ///< fixed point, AtlasParams::scales[3]
};
static_assert(offsetof(ViewTotals, max_angle_bits) == 16);
static_assert(offsetof(ViewTotals, angle_sum) == 24);
static_assert(sizeof(ViewTotals) == 32,
              "ViewTotals must match the Summary block in atlas_common.glsl");

/// struct PixelDeviation (std430): one pixel's comparison, kept on the device for the gather.
struct PixelDeviation {
    float value;
    float signed_depth;
    float reference_depth;
    std::uint32_t flags;
};
static_assert(sizeof(PixelDeviation) == 16, "PixelDeviation must match atlas_common.glsl");

}  // namespace glint::detail
