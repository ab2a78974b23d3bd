// The damage atlas: per-pixel deviations folded back onto the reference surface.
//
// Every covered pixel of a reference frame shows one reference triangle (its primitive id);
// the pixel's deviation is added to that triangle's three vertices with the pixel's
// barycentric weights. Per zoom level and per vertex the atlas keeps the maximum, the
// weighted mean and the number of observations of the angle deviation, the signed depth
// difference at the maximum, and the most frontal view that saw the vertex.
#pragma once

#include "mesh/mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace glint {

/// Per-vertex results of one zoom level.
struct ZoomAtlas {
    double footprint = 0.0;              ///< mesh units per pixel at this zoom
    std::vector<float> angle_max_deg;    ///< max over the pixels in the vertex's dual cell (0 where unseen)
    std::vector<float> angle_mean_deg;   ///< barycentric-weighted mean (0 where unseen)
    std::vector<float> depth_at_max;     ///< signed depth difference at the max (neg = dent)
    std::vector<float> depth_mean;       ///< weighted mean signed depth difference (NaN if none)
    std::vector<float> weight;           ///< sum of barycentric weights (observations)
    std::vector<std::uint32_t> count;    ///< pixels that touched the vertex
    std::vector<float> best_cos;         ///< cos(incidence) of the most frontal observation
    std::vector<std::int32_t> best_view; ///< view index of that observation (-1 = unseen)
    std::vector<std::int32_t> max_view;  ///< view index where the max was seen (-1 = unseen)
};

/// One pixel's contribution.
struct AtlasSample {
    std::uint32_t triangle = 0;
    std::array<float, 3> barycentric{};  ///< weights of the triangle's vertices, sum 1
    float angle_deg = 0.0f;
    float signed_depth = 0.0f;           ///< reference depth − examined depth (neg = dent)
    float cos_incidence = 1.0f;          ///< dot(surface normal, direction to the camera)
    bool valid_deviation = true;         ///< false: examined frame had no surface here
};

/// Accumulates samples of one zoom level (not thread-safe; one per worker, then merge).
class AtlasAccumulator {
public:
    AtlasAccumulator(const Mesh& reference, double footprint);
    /// Adds one pixel; samples with cos_incidence below min_cos still count as seen only if
    /// they pass: the caller filters by incidence (see SweepOptions::max_incidence_deg).
    void add(const AtlasSample& sample, std::int32_t view_index);
    /// Adds one observation of a single vertex (weight 1): the gathering pass, for vertices
    /// that no pixel centre fell on because the pixel is larger than their triangles.
    void add_vertex(std::uint32_t vertex, float angle_deg, float signed_depth, float cos_incidence,
                    std::int32_t view_index);
    /// Merges another accumulator of the same mesh and zoom.
    void merge(const AtlasAccumulator& other);
    /// Final per-vertex arrays.
    [[nodiscard]] ZoomAtlas finish() const;

private:
    const Mesh* mesh_;
    double footprint_;
    std::vector<float> max_;
    std::vector<float> depth_at_max_;
    std::vector<double> sum_;
    std::vector<double> weight_;
    std::vector<double> depth_sum_;
    std::vector<double> depth_weight_;
    std::vector<std::uint32_t> count_;
    std::vector<float> best_cos_;
    std::vector<std::int32_t> best_view_;
    std::vector<std::int32_t> max_view_;
};

/// Robust noise floor of a deviation field: median + k · 1.4826 · MAD over the seen vertices
/// (1.4826 makes the MAD a consistent estimate of σ for Gaussian noise).
struct NoiseFloor {
    double median = 0.0;
    double mad = 0.0;       ///< raw median absolute deviation
    double k = 0.0;
    double threshold = 0.0; ///< max(median + k·1.4826·MAD, minimum)
    double minimum = 0.0;
};
[[nodiscard]] NoiseFloor noise_floor(const std::vector<float>& values,
                                     const std::vector<std::uint8_t>& use, double k,
                                     double minimum);

}  // namespace glint
