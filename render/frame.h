// A rendered frame: what one view of a mesh shows, per pixel, as flat arrays.
//
// Both backends (Vulkan, Embree) produce exactly this, with the same conventions:
// - pixel (x, y) is stored at index y·width + x, row 0 at the top (geometry.h convention);
// - each pixel is the resolve of s×s sub-samples placed at (x + (i+0.5)/s, y + (j+0.5)/s);
// - a sub-sample is "covered" when its ray hits the mesh between the near and far planes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace glint {

/// Primitive id of a pixel that shows no triangle.
inline constexpr std::uint32_t kNoPrimitive = 0xFFFFFFFFu;
/// Depth of a pixel that shows no surface.
inline constexpr float kNoDepth = std::numeric_limits<float>::infinity();

/// Frame in which normals are expressed.
enum class NormalSpace {
    World,  ///< the mesh's coordinates (default; comparable across views)
    View,   ///< camera frame: x right, y up, z towards the viewer (geometry.h)
};

/// One rendered view. Uncovered pixels: normal (0,0,0), primitive_id kNoPrimitive,
/// depth kNoDepth, coverage 0.
struct Frame {
    int width = 0;
    int height = 0;
    NormalSpace normal_space = NormalSpace::World;
    /// 3 floats (x, y, z) per pixel: the renormalised mean of the per-sub-sample
    /// interpolated, normalised vertex normals over the *covered* sub-samples, so every
    /// covered pixel carries a unit normal even on silhouette edges (normalised by coverage).
    std::vector<float> normal;
    /// Triangle index into Mesh::triangles of the centre sub-sample (for even s the one just
    /// below-right of the pixel centre); when that one is uncovered, the first covered
    /// sub-sample in row-major order.
    std::vector<std::uint32_t> primitive_id;
    /// Linear depth along the viewing axis (camera -z), mesh units, mean over covered
    /// sub-samples.
    std::vector<float> depth;
    /// Share of covered sub-samples, 0…1 (1/s² steps).
    std::vector<float> coverage;
    /// Empty, or 2 floats per pixel: the weights (u, v) of corners 1 and 2 of primitive_id's
    /// triangle where the pixel's ray hit it (corner 0: 1 − u − v); NaN where uncovered. Only
    /// from CPU ray casting at s = 1 with FrameOptions::barycentrics.
    std::vector<float> barycentric;

    [[nodiscard]] std::size_t pixel_count() const {
        return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }
    [[nodiscard]] bool is_covered(std::size_t pixel) const { return coverage[pixel] > 0.0f; }
    /// Number of pixels with coverage > 0.
    [[nodiscard]] std::size_t covered_count() const;
};

/// A frame of the given size with every pixel uncovered.
[[nodiscard]] Frame make_empty_frame(int width, int height, NormalSpace space = NormalSpace::World);

/// Read-only rows [y0, y0 + height) of a frame, with the frame's conventions: pixel (x, y0 + r)
/// at index r·width + x of each array. What a frame streamed by bands hands on
/// (render_view_pair_rows, render/renderer.h).
struct FrameRows {
    int width = 0;
    int height = 0;  ///< rows held
    int y0 = 0;      ///< index of the first row in the whole frame
    NormalSpace normal_space = NormalSpace::World;
    std::span<const float> normal;  ///< 3 floats per pixel
    std::span<const std::uint32_t> primitive_id;
    std::span<const float> depth;
    std::span<const float> coverage;

    [[nodiscard]] std::size_t pixel_count() const {
        return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }
};

/// Rows [y0, y1) of `frame`. \pre 0 ≤ y0 ≤ y1 ≤ frame.height.
[[nodiscard]] FrameRows frame_rows(const Frame& frame, int y0, int y1);

}  // namespace glint
