// What the sweep's two atlas paths share (DESIGN.md "back-projection"): the per-pixel metrics a
// comparison can fold, the numbers one view yields, and the per-vertex running totals of one
// zoom level. The CPU path (scanner/atlas.h AtlasAccumulator) keeps its state in an AtlasTotals,
// the GPU path (render/gpu_atlas.h) reads one back per zoom; scanner's finish_atlas() turns
// either into the atlas.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace glint {

/// A pixel's deviation between a reference and an examined frame (scanner/metric.h describes
/// each for people: name, unit, ranges).
enum class Metric {
    AngleDeg,  ///< angle between the reference and the examined unit normal, degrees
    RgbAbs,    ///< mean |ΔR|, |ΔG|, |ΔB| of the 8-bit normal colours (0.5·n + 0.5), 0…255
};

/// What one view showed.
struct ViewNumbers {
    std::size_t reference_pixels = 0;  ///< reference pixels covered (at the minimum coverage)
    std::size_t compared = 0;          ///< covered in both frames
    std::size_t reference_only = 0;    ///< the reference without examined surface behind
    std::size_t examined_only = 0;
    double max_angle_deg = 0.0;
    double mean_angle_deg = 0.0;
};

/// Per-vertex running totals of one zoom level: every observation of a vertex folded in
/// (weights are the pixels' barycentric weights; a gathered vertex weighs 1).
struct AtlasTotals {
    std::vector<float> value_max;        ///< largest value at the vertex's nearest pixels (0: none)
    std::vector<float> depth_at_max;     ///< signed depth there (NaN: missing surface)
    std::vector<std::int32_t> max_view;  ///< view of the maximum (-1: none)
    std::vector<double> weight;          ///< Σ w
    std::vector<double> value_sum;       ///< Σ w·value
    std::vector<double> missing_weight;  ///< Σ w where no examined surface was behind the pixel
    std::vector<double> depth_sum;       ///< Σ w·signed depth
    std::vector<double> depth_weight;    ///< Σ w where the depth was finite
    std::vector<std::uint32_t> count;    ///< observations
    std::vector<float> best_cos;         ///< most frontal cos(incidence) (-2: none)
    std::vector<std::int32_t> best_view;  ///< view of that observation (-1: none)
    /// Fixed-point steps of the GPU's sums (weight and missing_weight, value_sum, depth_sum):
    /// each observation was rounded to half a step. 0: exact double sums (the CPU path).
    double weight_resolution = 0.0;
    double value_resolution = 0.0;
    double depth_resolution = 0.0;

    /// Totals of `vertices` vertices that nothing observed yet.
    [[nodiscard]] static AtlasTotals none(std::size_t vertices) {
        AtlasTotals t;
        t.value_max.assign(vertices, 0.0f);
        t.depth_at_max.assign(vertices, 0.0f);
        t.max_view.assign(vertices, -1);
        t.weight.assign(vertices, 0.0);
        t.value_sum.assign(vertices, 0.0);
        t.missing_weight.assign(vertices, 0.0);
        t.depth_sum.assign(vertices, 0.0);
        t.depth_weight.assign(vertices, 0.0);
        t.count.assign(vertices, 0u);
        t.best_cos.assign(vertices, -2.0f);
        t.best_view.assign(vertices, -1);
        return t;
    }
    [[nodiscard]] std::size_t size() const { return value_max.size(); }
};

}  // namespace glint
