// The damage atlas: per-pixel deviations accumulated on the reference surface.
//
// Back-projection (scanner/backproject.h) turns each covered pixel of a reference frame into
// samples on that pixel's reference triangle; the accumulator folds them per vertex and per
// zoom level into the maximum, the weighted mean and the number of observations of the
// sweep's metric (scanner/metric.h), the signed depth difference, the share of observations
// that found no examined surface, and the most frontal view that saw the vertex.
#pragma once

#include "mesh/mesh.h"
#include "render/atlas_totals.h"

#include <array>
#include <cstdint>
#include <vector>

namespace glint {

/// Per-vertex results of one zoom level.
struct ZoomAtlas {
    double footprint = 0.0;  ///< mesh units per pixel at this zoom
    std::vector<float>
        value_max;  ///< metric: max over the pixels in the vertex's dual cell (0 where unseen)
    std::vector<float> value_mean;    ///< metric: barycentric-weighted mean (0 where unseen)
    std::vector<float> depth_at_max;  ///< signed depth difference at the max (neg = dent)
    std::vector<float> depth_mean;    ///< weighted mean signed depth difference (NaN if none)
    std::vector<float>
        missing;  ///< share of the weight where no examined surface was behind the pixel
    std::vector<float> weight;            ///< sum of barycentric weights (observations)
    std::vector<std::uint32_t> count;     ///< pixels that touched the vertex
    std::vector<float> best_cos;          ///< cos(incidence) of the most frontal observation
    std::vector<std::int32_t> best_view;  ///< view index of that observation (-1 = unseen)
    std::vector<std::int32_t> max_view;   ///< view index where the max was seen (-1 = unseen)
};

/// The atlas of one zoom level from its running totals, by either path: means are the sums
/// over their weights (0 where unseen; depth NaN where no depth was seen).
[[nodiscard]] ZoomAtlas finish_atlas(AtlasTotals totals, double footprint);

/// One observation: a pixel on a triangle, or (gathering) a single vertex.
struct AtlasSample {
    std::uint32_t triangle = 0;          ///< add(): the pixel's reference triangle
    std::array<float, 3> barycentric{};  ///< add(): weights of the triangle's vertices, sum 1
    float value = 0.0f;                  ///< the metric's value
    float signed_depth = 0.0f;   ///< reference depth − examined depth (neg = dent); NaN = none
    float cos_incidence = 1.0f;  ///< dot(surface normal, direction to the camera)
    bool valid = true;           ///< false: the pixel was not compared (edge pixel)
    bool missing = false;        ///< no examined surface behind the pixel
};

/// Accumulates samples of one zoom level (not thread-safe; one per worker, then merge).
class AtlasAccumulator {
  public:
    AtlasAccumulator(const Mesh& reference, double footprint);
    /// Adds one pixel on sample.triangle. The caller has applied the coverage rule.
    void add(const AtlasSample& sample, std::int32_t view_index);
    /// add() for the triangle's corners in [first, last) only: the share of one worker when
    /// the vertices are split between workers (the others add the remaining corners).
    void add(const AtlasSample& sample, std::int32_t view_index, std::uint32_t first,
             std::uint32_t last);
    /// Adds one observation of a single vertex (weight 1): the gathering pass, for vertices
    /// that no pixel centre fell on because the pixel is larger than their triangles.
    void add_vertex(std::uint32_t vertex, const AtlasSample& sample, std::int32_t view_index);
    /// Merges another accumulator of the same mesh and zoom.
    void merge(const AtlasAccumulator& other);
    /// Final per-vertex arrays (finish_atlas of the totals); the accumulator keeps its totals.
    [[nodiscard]] ZoomAtlas finish() const&;
    /// The same, taking the totals instead of copying them: at 1M vertices the totals are
    /// ~60 MB, and the copy was the run's peak memory (2M triangles: 603 MiB).
    [[nodiscard]] ZoomAtlas finish() &&;

    /// The running totals (the GPU path reads the same state back from the device).
    [[nodiscard]] const AtlasTotals& totals() const { return totals_; }

  private:
    void observe(std::uint32_t v, float w, bool nearest, const AtlasSample& s,
                 std::int32_t view_index);

    const Mesh* mesh_;
    double footprint_;
    AtlasTotals totals_;
};

}  // namespace glint
