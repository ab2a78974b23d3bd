// Per-view comparison of a reference frame and the fitted examined frame (same camera).
//
// Per pixel, where both frames fully cover it:
//   angle_deg    = angle between the two unit normals (the primary metric);
//   signed_depth = reference depth − examined depth along the ray: the examined surface
//                  lies farther from the camera (inward, a dent or loss) → negative;
//                  nearer (outward, a bump or growth) → positive;
// The metric a sweep folds onto the surface (scanner/metric.h) fills DeviationMap::value.
// Silhouette change: pixels covered in one frame only.
#pragma once

#include "render/frame.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace glint {

/// Read-only view of a rendered frame (row-major, top row first).
struct FrameView {
    int width = 0;
    int height = 0;
    std::span<const float> normal;             ///< 3 floats per pixel, unit where covered
    std::span<const std::uint32_t> primitive;  ///< triangle id, kNoPrimitive where none
    std::span<const float> depth;              ///< linear depth, mesh units
    std::span<const float> coverage;           ///< 0…1 share of the pixel's sub-samples hit
};

enum class Silhouette : std::uint8_t { Same = 0, ReferenceOnly = 1, ExaminedOnly = 2 };

struct CompareOptions {
    /// A pixel counts as covered when at least this share of its sub-samples hit the surface;
    /// partly covered edge pixels average surface with background and are not compared.
    float min_coverage = 0.999f;
};

struct DeviationMap {
    int width = 0;
    int height = 0;
    std::vector<float> angle_deg;     ///< NaN where not compared
    std::vector<float> signed_depth;  ///< NaN where not compared
    std::vector<float> value;  ///< the sweep's metric (scanner/metric.h); NaN where not compared
    std::vector<std::uint8_t> silhouette;  ///< Silhouette per pixel
    std::size_t compared = 0;
    std::size_t reference_only = 0;
    std::size_t examined_only = 0;
    double max_angle_deg = 0.0;
    double mean_angle_deg = 0.0;
};

/// Read-only view of a rendered frame.
[[nodiscard]] FrameView frame_view(const Frame& frame);
/// Read-only view of rows of a frame (a frame of rows.height rows).
[[nodiscard]] FrameView frame_view(const FrameRows& rows);

/// Compares two frames of the same size (angle, signed depth, silhouette; `value` is left
/// empty: see scanner/metric.h). \throw InputError when sizes differ.
[[nodiscard]] DeviationMap compare_frames(const FrameView& reference, const FrameView& examined,
                                          const CompareOptions& options = {});

/// compare_frames' per-pixel rule for every pixel of two views of one size, written into the
/// spans (one entry per pixel): what a sweep runs on each band of rows as it is rendered.
/// \pre the views have one size and the spans their pixel count.
void compare_pixels(const FrameView& reference, const FrameView& examined,
                    const CompareOptions& options, std::span<float> angle_deg,
                    std::span<float> signed_depth, std::span<std::uint8_t> silhouette);

/// The counts and the largest and mean angle of a map (DeviationMap's statistics) from its
/// per-pixel values, summed in pixel order.
void summarise(DeviationMap& map);

}  // namespace glint
