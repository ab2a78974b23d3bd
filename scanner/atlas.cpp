#include "scanner/atlas.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

namespace glint {

AtlasAccumulator::AtlasAccumulator(const Mesh& reference, double footprint)
    : mesh_(&reference),
      footprint_(footprint),
      totals_(AtlasTotals::none(reference.vertex_count())) {}

void AtlasAccumulator::observe(std::uint32_t v, float w, bool nearest, const AtlasSample& s,
                               std::int32_t view_index) {
    AtlasTotals& t = totals_;
    ++t.count[v];
    if (s.cos_incidence > t.best_cos[v]) {
        t.best_cos[v] = s.cos_incidence;
        t.best_view[v] = view_index;
    }
    if (!s.valid) return;
    t.weight[v] += w;
    t.value_sum[v] += static_cast<double>(w) * s.value;
    if (s.missing) t.missing_weight[v] += w;
    if (std::isfinite(s.signed_depth)) {
        t.depth_weight[v] += w;
        t.depth_sum[v] += static_cast<double>(w) * s.signed_depth;
    }
    if (nearest && (s.value > t.value_max[v] || t.max_view[v] < 0)) {
        t.value_max[v] = s.value;
        t.depth_at_max[v] = s.signed_depth;
        t.max_view[v] = view_index;
    }
}

void AtlasAccumulator::add(const AtlasSample& s, std::int32_t view_index) {
    add(s, view_index, 0, static_cast<std::uint32_t>(totals_.size()));
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
    GLINT_ASSERT(v < totals_.size(), "vertex beyond the reference mesh");
    observe(v, 1.0f, true, s, view_index);
}

void AtlasAccumulator::merge(const AtlasAccumulator& other) {
    GLINT_ASSERT(other.mesh_ == mesh_, "merging atlases of different meshes");
    AtlasTotals& t = totals_;
    const AtlasTotals& o = other.totals_;
    for (std::size_t v = 0; v < t.size(); ++v) {
        t.count[v] += o.count[v];
        t.value_sum[v] += o.value_sum[v];
        t.weight[v] += o.weight[v];
        t.depth_sum[v] += o.depth_sum[v];
        t.depth_weight[v] += o.depth_weight[v];
        t.missing_weight[v] += o.missing_weight[v];
        if (o.best_cos[v] > t.best_cos[v]) {
            t.best_cos[v] = o.best_cos[v];
            t.best_view[v] = o.best_view[v];
        }
        if (o.max_view[v] >= 0 && (t.max_view[v] < 0 || o.value_max[v] > t.value_max[v])) {
            t.value_max[v] = o.value_max[v];
            t.depth_at_max[v] = o.depth_at_max[v];
            t.max_view[v] = o.max_view[v];
        }
    }
}

ZoomAtlas AtlasAccumulator::finish() const& { return finish_atlas(totals_, footprint_); }

ZoomAtlas AtlasAccumulator::finish() && { return finish_atlas(std::move(totals_), footprint_); }

ZoomAtlas finish_atlas(AtlasTotals t, double footprint) {
    ZoomAtlas a;
    a.footprint = footprint;
    const std::size_t n = t.size();
    // Array by array, each total freed once it is read: the totals (doubles) are not held
    // beside every finished array at once.
    const auto release = [](auto& v) { std::decay_t<decltype(v)>().swap(v); };
    a.value_mean.resize(n);
    for (std::size_t v = 0; v < n; ++v)
        a.value_mean[v] = t.weight[v] > 0 ? static_cast<float>(t.value_sum[v] / t.weight[v]) : 0.0f;
    release(t.value_sum);
    a.missing.resize(n);
    for (std::size_t v = 0; v < n; ++v)
        a.missing[v] =
            t.weight[v] > 0 ? static_cast<float>(t.missing_weight[v] / t.weight[v]) : 0.0f;
    release(t.missing_weight);
    a.depth_mean.resize(n);
    for (std::size_t v = 0; v < n; ++v)
        a.depth_mean[v] = t.depth_weight[v] > 0
                              ? static_cast<float>(t.depth_sum[v] / t.depth_weight[v])
                              : std::numeric_limits<float>::quiet_NaN();
    release(t.depth_sum);
    release(t.depth_weight);
    a.weight.resize(n);
    for (std::size_t v = 0; v < n; ++v) a.weight[v] = static_cast<float>(t.weight[v]);
    release(t.weight);
    a.best_cos.resize(n);
    for (std::size_t v = 0; v < n; ++v) a.best_cos[v] = t.best_view[v] >= 0 ? t.best_cos[v] : 0.0f;
    release(t.best_cos);
    a.value_max = std::move(t.value_max);
    a.depth_at_max = std::move(t.depth_at_max);
    a.count = std::move(t.count);
    a.best_view = std::move(t.best_view);
    a.max_view = std::move(t.max_view);
    return a;
}

}  // namespace glint
