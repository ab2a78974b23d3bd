#include "scanner/atlas.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {

AtlasAccumulator::AtlasAccumulator(const Mesh& reference, double footprint)
    : mesh_(&reference),
      footprint_(footprint),
      max_(reference.vertex_count(), 0.0f),
      depth_at_max_(reference.vertex_count(), 0.0f),
      sum_(reference.vertex_count(), 0.0),
      weight_(reference.vertex_count(), 0.0),
      depth_sum_(reference.vertex_count(), 0.0),
      depth_weight_(reference.vertex_count(), 0.0),
      missing_weight_(reference.vertex_count(), 0.0),
      count_(reference.vertex_count(), 0u),
      best_cos_(reference.vertex_count(), -2.0f),
      best_view_(reference.vertex_count(), -1),
      max_view_(reference.vertex_count(), -1) {}

void AtlasAccumulator::observe(std::uint32_t v, float w, bool nearest, const AtlasSample& s,
                               std::int32_t view_index) {
    ++count_[v];
    if (s.cos_incidence > best_cos_[v]) {
        best_cos_[v] = s.cos_incidence;
        best_view_[v] = view_index;
    }
    if (!s.valid) return;
    weight_[v] += w;
    sum_[v] += static_cast<double>(w) * s.value;
    if (s.missing) missing_weight_[v] += w;
    if (std::isfinite(s.signed_depth)) {
        depth_weight_[v] += w;
        depth_sum_[v] += static_cast<double>(w) * s.signed_depth;
    }
    if (nearest && (s.value > max_[v] || max_view_[v] < 0)) {
        max_[v] = s.value;
        depth_at_max_[v] = s.signed_depth;
        max_view_[v] = view_index;
    }
}

void AtlasAccumulator::add(const AtlasSample& s, std::int32_t view_index) {
    add(s, view_index, 0, static_cast<std::uint32_t>(max_.size()));
}

void AtlasAccumulator::add(const AtlasSample& s, std::int32_t view_index, std::uint32_t first,
                           std::uint32_t last) {
    GLINT_ASSERT(s.triangle < mesh_->triangles.size(), "primitive id beyond the reference mesh");
    const auto& tri = mesh_->triangles[s.triangle];
    // The maximum goes to the vertex whose dual cell holds the pixel (largest weight) only,
    // so it does not spread by a ring of triangles; the mean and the counts use all weights.
    const std::size_t nearest = static_cast<std::size_t>(
        std::max_element(s.barycentric.begin(), s.barycentric.end()) - s.barycentric.begin());
    for (std::size_t k = 0; k < 3; ++k) {
        // note: a pixel whose centre lies on the far side of a vertex (weight ~0) says
        // nothing about that vertex; 1e-3 skips those without losing real observations.
        if (s.barycentric[k] < 1e-3f || tri[k] < first || tri[k] >= last) continue;
        observe(tri[k], s.barycentric[k], k == nearest, s, view_index);
    }
}

void AtlasAccumulator::add_vertex(std::uint32_t v, const AtlasSample& s, std::int32_t view_index) {
    GLINT_ASSERT(v < max_.size(), "vertex beyond the reference mesh");
    observe(v, 1.0f, true, s, view_index);
}

void AtlasAccumulator::merge(const AtlasAccumulator& o) {
    GLINT_ASSERT(o.mesh_ == mesh_, "merging atlases of different meshes");
    for (std::size_t v = 0; v < max_.size(); ++v) {
        count_[v] += o.count_[v];
        sum_[v] += o.sum_[v];
        weight_[v] += o.weight_[v];
        depth_sum_[v] += o.depth_sum_[v];
        depth_weight_[v] += o.depth_weight_[v];
        missing_weight_[v] += o.missing_weight_[v];
        if (o.best_cos_[v] > best_cos_[v]) {
            best_cos_[v] = o.best_cos_[v];
            best_view_[v] = o.best_view_[v];
        }
        if (o.max_view_[v] >= 0 && (max_view_[v] < 0 || o.max_[v] > max_[v])) {
            max_[v] = o.max_[v];
            depth_at_max_[v] = o.depth_at_max_[v];
            max_view_[v] = o.max_view_[v];
        }
    }
}

ZoomAtlas AtlasAccumulator::finish() const {
    ZoomAtlas a;
    a.footprint = footprint_;
    const std::size_t n = max_.size();
    a.value_max = max_;
    a.depth_at_max = depth_at_max_;
    a.count = count_;
    a.best_view = best_view_;
    a.max_view = max_view_;
    a.value_mean.resize(n);
    a.weight.resize(n);
    a.missing.resize(n);
    a.best_cos.resize(n);
    a.depth_mean.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
        a.weight[v] = static_cast<float>(weight_[v]);
        a.value_mean[v] = weight_[v] > 0 ? static_cast<float>(sum_[v] / weight_[v]) : 0.0f;
        a.missing[v] = weight_[v] > 0 ? static_cast<float>(missing_weight_[v] / weight_[v]) : 0.0f;
        a.depth_mean[v] = depth_weight_[v] > 0
                              ? static_cast<float>(depth_sum_[v] / depth_weight_[v])
                              : std::numeric_limits<float>::quiet_NaN();
        a.best_cos[v] = best_view_[v] >= 0 ? best_cos_[v] : 0.0f;
    }
    return a;
}

}  // namespace glint
