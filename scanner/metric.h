// Metrics: what one pixel's deviation between a reference and an examined frame is.
//
// A metric is a descriptor, not a branch: the atlas, the thresholds, the histogram, the
// report keys, the per-view pictures and the mosaics all read their names, units, ranges
// and colour scales from it. Adding a metric is one more entry in metrics() (metric.cpp)
// and a test.
//
//   angle  angle between the reference and the examined unit normal, degrees (primary)
//   rgb    the light-reflection paper's metric: mean over R, G, B of |c_ref − c_exa| on the
//          8-bit normal colours (rgb = 0.5·n + 0.5 quantised), 0…255
#pragma once

#include "render/atlas_totals.h"  // enum class Metric
#include "scanner/compare.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

struct MetricDescriptor {
    Metric id = Metric::AngleDeg;
    std::string_view name;         ///< "angle": option value, atlas scalar and report key prefix
    std::string_view unit;         ///< "deg": report keys and CSV headers ("angle_deg")
    std::string_view symbol;       ///< "°": after numbers printed for people
    std::string_view title;        ///< "angle deviation": picture titles
    std::string_view description;  ///< one line for --help and the report
    /// Value of a reference pixel with no examined surface behind it (surface missing).
    float missing_value = 90.0f;
    double max_value = 180.0;     ///< largest possible value (thresholds must lie in (0, max])
    double histogram_max = 90.0;  ///< histogram covers [0, histogram_max), last bin ≥ it
    double histogram_bin = 1.0;   ///< bin width
    double color_max = 20.0;      ///< per-view heat maps and mosaics: colour scale 0…color_max
    /// Per-pixel values where the comparison found an angle (NaN elsewhere), written into
    /// `value`; both frames (or bands of rows of them) and both spans one size. Pixel by
    /// pixel, so a sweep computes it band by band.
    void (*compute)(const FrameView& reference, const FrameView& examined,
                    std::span<const float> angle_deg, std::span<float> value) = nullptr;
};

/// Every metric glint knows, the primary first.
[[nodiscard]] std::span<const MetricDescriptor> metrics();
/// The descriptor of a metric.
[[nodiscard]] const MetricDescriptor& describe(Metric metric);
/// By name ("angle", "rgb"). \throw InputError listing the names.
[[nodiscard]] Metric parse_metric(std::string_view name);
/// The metric's name.
[[nodiscard]] std::string to_string(Metric metric);

/// compare_frames plus the metric's per-pixel value (DeviationMap::value).
[[nodiscard]] DeviationMap compare_frames(const FrameView& reference, const FrameView& examined,
                                          const CompareOptions& options, Metric metric);

}  // namespace glint
