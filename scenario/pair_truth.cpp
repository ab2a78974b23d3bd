#include "scenario/pair_truth.h"

#include "mesh/components.h"
#include "mesh/error.h"
#include "registration/closest_point.h"

#include <cmath>
#include <limits>
#include <set>

namespace glint {

std::vector<float> vertex_distances(const Mesh& reference, const Mesh& surface) {
    const ClosestPointIndex index(surface);
    std::vector<Vec3d> points;
    points.reserve(reference.vertex_count());
    for (const auto& p : reference.positions) points.push_back(p.cast<double>());
    const auto hits = index.closest(points);
    std::vector<float> out(hits.size());
    for (std::size_t v = 0; v < hits.size(); ++v) out[v] = static_cast<float>(hits[v].distance);
    return out;
}

PairTruth erosion_truth(const Mesh& reference, const Mesh& noiseless_reference,
                        const Mesh& noiseless_examined, std::span<const Erosion> erosions,
                        double reach, double depth) {
    const std::size_t n = reference.vertex_count();
    PairTruth truth;
    truth.damaged.assign(n, 0);
    truth.damage_id.assign(n, 0);
    if (erosions.empty() || n == 0) return truth;
    const std::vector<float> before = noiseless_reference.triangle_count() > 0
                                          ? vertex_distances(reference, noiseless_reference)
                                          : std::vector<float>(n, 0.0f);
    const std::vector<float> after =
        noiseless_examined.triangle_count() > 0
            ? vertex_distances(reference, noiseless_examined)
            : std::vector<float>(n, std::numeric_limits<float>::infinity());
    for (std::size_t v = 0; v < n; ++v) {
        const Vec3d p = reference.positions[v].cast<double>();
        std::int32_t id = 0;
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t e = 0; e < erosions.size(); ++e) {
            const double outside = (p - erosions[e].center).norm() - erosions[e].radius;
            if (outside <= reach && outside < nearest) {
                nearest = outside;
                id = static_cast<std::int32_t>(e + 1);
            }
        }
        if (id == 0 || !(static_cast<double>(after[v]) - before[v] >= depth)) continue;
        truth.damaged[v] = 1;
        truth.damage_id[v] = id;
    }
    return truth;
}

PairTruth distance_truth(const Mesh& reference, const Mesh& damaged_examined,
                         const std::vector<std::int32_t>& footprint,
                         const std::vector<DamageSpec>& damages) {
    const std::size_t n = reference.vertex_count();
    GLINT_ASSERT(footprint.size() == n, "footprint does not match the reference");
    PairTruth truth;
    truth.damaged.assign(n, 0);
    truth.damage_id.assign(n, 0);
    const std::vector<float> distance = vertex_distances(reference, damaged_examined);
    for (std::size_t v = 0; v < n; ++v) {
        const std::int32_t id = footprint[v];
        if (id <= 0 || static_cast<std::size_t>(id) > damages.size()) continue;
        const double depth = damages[static_cast<std::size_t>(id - 1)].depth;
        if (distance[v] > kDamageLabelThreshold * depth) {
            truth.damaged[v] = 1;
            truth.damage_id[v] = id;
        }
    }
    return truth;
}

RegionTally tally_regions(const std::vector<std::int32_t>& region_of_vertex, const PairTruth* truth,
                          const std::vector<float>& true_distance, double min_true_distance) {
    RegionTally t;
    std::set<std::int32_t> regions, true_regions, damages, detected;
    for (std::size_t v = 0; v < region_of_vertex.size(); ++v) {
        const std::int32_t r = region_of_vertex[v];
        const std::int32_t d = truth && !truth->damage_id.empty() ? truth->damage_id[v] : 0;
        if (d > 0) damages.insert(d);
        if (r <= 0) continue;
        regions.insert(r);
        if (d > 0) {
            true_regions.insert(r);
            detected.insert(d);
        }
        if (!true_distance.empty() && true_distance[v] < min_true_distance)
            ++t.close_region_vertices;
    }
    t.regions = regions.size();
    t.false_regions = truth ? regions.size() - true_regions.size() : 0;
    t.damages = damages.size();
    t.damages_detected = detected.size();
    return t;
}

BaselineResult distance_baseline(const Mesh& reference, const std::vector<float>& distance,
                                 double threshold) {
    GLINT_ASSERT(distance.size() == reference.vertex_count(),
                 "distance does not match the reference");
    BaselineResult b;
    b.threshold = threshold;
    std::vector<std::uint8_t> mask(distance.size());
    for (std::size_t v = 0; v < distance.size(); ++v) mask[v] = std::abs(distance[v]) > threshold;
    std::vector<std::int32_t> component;
    b.regions = masked_components(reference, mask, component);
    b.region_of_vertex.resize(component.size());
    for (std::size_t v = 0; v < component.size(); ++v)
        b.region_of_vertex[v] = component[v] + 1;  // −1 → 0
    return b;
}

}  // namespace glint
