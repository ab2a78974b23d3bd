#include "scanner/coverage.h"

#include "mesh/components.h"
#include "mesh/error.h"

#include <algorithm>

namespace glint {

Coverage coverage_of(const Mesh& reference, const ZoomAtlas& atlas, const std::optional<Roi>& roi) {
    const std::size_t n = reference.vertex_count();
    GLINT_ASSERT(atlas.weight.size() == n && atlas.count.size() == n,
                 "atlas does not match the mesh");
    const auto areas = vertex_areas(reference);
    Coverage c;
    c.seen.assign(n, 0);
    for (std::size_t v = 0; v < n; ++v) {
        const bool asked = !roi || roi->contains(v, reference.positions[v].cast<double>());
        if (!asked) continue;
        c.asked_area += areas[v];
        // Observed: some observation passed the incidence rule (count), with a compared value
        // (weight) or at least a missing-surface verdict.
        c.seen[v] = atlas.weight[v] > 0.0f ? 1 : 0;
        if (c.seen[v]) c.seen_area += areas[v];
    }
    c.fraction = c.asked_area > 0 ? c.seen_area / c.asked_area : 0.0;
    return c;
}

UnseenSummary unseen_patches(const Mesh& reference, const std::vector<std::uint8_t>& seen,
                             const std::optional<Roi>& roi) {
    const std::size_t n = reference.vertex_count();
    std::vector<std::uint8_t> unseen(n, 0);
    for (std::size_t v = 0; v < n; ++v)
        unseen[v] = !seen[v] && (!roi || roi->contains(v, reference.positions[v].cast<double>()));
    std::vector<std::int32_t> patch;
    const std::size_t count = masked_components(reference, unseen, patch);
    const auto areas = vertex_areas(reference);
    UnseenSummary s;
    s.patches.resize(count);
    std::vector<Vec3d> weighted(count, Vec3d::Zero());
    for (std::size_t v = 0; v < n; ++v) {
        if (patch[v] < 0) continue;
        auto& p = s.patches[static_cast<std::size_t>(patch[v])];
        ++p.vertices;
        p.area += areas[v];
        weighted[static_cast<std::size_t>(patch[v])] +=
            areas[v] * reference.positions[v].cast<double>();
        ++s.vertices;
        s.area += areas[v];
    }
    for (std::size_t i = 0; i < count; ++i)
        if (s.patches[i].area > 0) s.patches[i].centroid = weighted[i] / s.patches[i].area;
    std::stable_sort(s.patches.begin(), s.patches.end(),
                     [](const UnseenPatch& a, const UnseenPatch& b) { return a.area > b.area; });
    return s;
}

}  // namespace glint
