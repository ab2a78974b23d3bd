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
      count_(reference.vertex_count(), 0u),
      best_cos_(reference.vertex_count(), -2.0f),
      best_view_(reference.vertex_count(), -1),
      max_view_(reference.vertex_count(), -1) {}

void AtlasAccumulator::add(const AtlasSample& s, std::int32_t view_index) {
    GLINT_ASSERT(s.triangle < mesh_->triangles.size(), "primitive id beyond the reference mesh");
    const auto& tri = mesh_->triangles[s.triangle];
    // The maximum goes to the vertex whose dual cell holds the pixel (largest weight) only,
    // so it does not spread by a ring of triangles; the mean and the counts use all weights.
    const std::size_t nearest = static_cast<std::size_t>(
        std::max_element(s.barycentric.begin(), s.barycentric.end()) - s.barycentric.begin());
    for (std::size_t k = 0; k < 3; ++k) {
        const float w = s.barycentric[k];
        // note: a pixel whose centre lies on the far side of a vertex (weight ~0) says
        // nothing about that vertex; 1e-3 skips those without losing real observations.
        if (w < 1e-3f) continue;
        const auto v = tri[k];
        ++count_[v];
        if (s.cos_incidence > best_cos_[v]) {
            best_cos_[v] = s.cos_incidence;
            best_view_[v] = view_index;
        }
        if (!s.valid_deviation) continue;
        weight_[v] += w;
        sum_[v] += static_cast<double>(w) * s.angle_deg;
        if (std::isfinite(s.signed_depth)) {
            depth_weight_[v] += w;
            depth_sum_[v] += static_cast<double>(w) * s.signed_depth;
        }
        if (k == nearest && (s.angle_deg > max_[v] || max_view_[v] < 0)) {
            max_[v] = s.angle_deg;
            depth_at_max_[v] = s.signed_depth;
            max_view_[v] = view_index;
        }
    }
}

void AtlasAccumulator::add_vertex(std::uint32_t v, float angle_deg, float signed_depth, float cos_incidence,
                                  std::int32_t view_index) {
    GLINT_ASSERT(v < max_.size(), "vertex beyond the reference mesh");
    ++count_[v];
    if (cos_incidence > best_cos_[v]) {
        best_cos_[v] = cos_incidence;
        best_view_[v] = view_index;
    }
    weight_[v] += 1.0;
    sum_[v] += angle_deg;
    if (std::isfinite(signed_depth)) {
        depth_weight_[v] += 1.0;
        depth_sum_[v] += signed_depth;
    }
    if (angle_deg > max_[v] || max_view_[v] < 0) {
        max_[v] = angle_deg;
        depth_at_max_[v] = signed_depth;
        max_view_[v] = view_index;
    }
}

void AtlasAccumulator::merge(const AtlasAccumulator& o) {
    GLINT_ASSERT(o.mesh_ == mesh_, "merging atlases of different meshes");
    for (std::size_t v = 0; v < max_.size(); ++v) {
        count_[v] += o.count_[v];
        sum_[v] += o.sum_[v];
        weight_[v] += o.weight_[v];
        depth_sum_[v] += o.depth_sum_[v];
        depth_weight_[v] += o.depth_weight_[v];
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
    a.angle_max_deg = max_;
    a.depth_at_max = depth_at_max_;
    a.count = count_;
    a.best_view = best_view_;
    a.max_view = max_view_;
    a.angle_mean_deg.resize(n);
    a.weight.resize(n);
    a.best_cos.resize(n);
    a.depth_mean.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
        a.weight[v] = static_cast<float>(weight_[v]);
        a.angle_mean_deg[v] = weight_[v] > 0 ? static_cast<float>(sum_[v] / weight_[v]) : 0.0f;
        a.depth_mean[v] = depth_weight_[v] > 0 ? static_cast<float>(depth_sum_[v] / depth_weight_[v])
                                               : std::numeric_limits<float>::quiet_NaN();
        a.best_cos[v] = best_view_[v] >= 0 ? best_cos_[v] : 0.0f;
    }
    return a;
}

NoiseFloor noise_floor(const std::vector<float>& values, const std::vector<std::uint8_t>& use,
                       double k, double minimum) {
    std::vector<float> x;
    x.reserve(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        if (use[i]) x.push_back(values[i]);
    NoiseFloor f;
    f.k = k;
    f.minimum = minimum;
    if (x.empty()) {
        f.threshold = minimum;
        return f;
    }
    auto median_of = [](std::vector<float>& v) {
        const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
        std::nth_element(v.begin(), mid, v.end());
        return static_cast<double>(*mid);
    };
    f.median = median_of(x);
    for (auto& e : x) e = static_cast<float>(std::abs(e - f.median));
    f.mad = median_of(x);
    f.threshold = std::max(f.median + k * 1.4826 * f.mad, minimum);
    return f;
}

}  // namespace glint
