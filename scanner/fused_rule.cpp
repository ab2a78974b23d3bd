// The fused rule: a region needs both a change of shape and a change of the normal field.
// See scanner/decision.h for the rule; the reasons for each step are here.
#include "scanner/detail/fused_rule.h"

#include "mesh/components.h"
#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glint::detail {

namespace {

// A vertex whose examined surface is missing: most observations found none behind it, or its
// closest examined point lies on a border of the examined mesh while the distance is beyond
// the shape floor (a hole or a cut edge, not a surface that moved).
// note: 0.5 — the majority of the observation weight, the same rule as RegionOptions.
std::vector<std::uint8_t> missing_mask(const DecisionEvidence& e, const std::vector<float>& excess, const Floor& shape) {
    const std::size_t n = excess.size();
    std::vector<std::uint8_t> m(n, 0);
    for (std::size_t v = 0; v < n; ++v) {
        if (!e.coverage->seen[v]) continue;
        const bool border = e.at_border && (*e.at_border)[v] && std::abs(excess[v]) >= shape.value;
        m[v] = e.atlas->missing[v] > 0.5f || border;
    }
    return m;
}

// note: 1/2 of the tolerance (kTessellationTolerance·h·θ) — on the jaw remeshed at 1.2× a
// chord's offset on the convex condyle reached 0.06–0.09 mm where h·θ was ~0.44 mm.
constexpr double kGrowToleranceShare = 0.5;

struct Group {
    float peak_excess = 0.0f;    // largest signed excess magnitude (in the group's sign)
    float peak_distance = 0.0f;  // largest signed distance magnitude
    float max_normal = 0.0f;
};

// Vertex neighbours through mesh edges, in compressed rows: neighbours of v are
// index[offset[v] .. offset[v + 1]).
struct Adjacency {
    std::vector<std::uint32_t> offset;
    std::vector<std::uint32_t> index;
};

Adjacency adjacency(const Mesh& mesh) {
    const std::size_t n = mesh.vertex_count();
    Adjacency a;
    a.offset.assign(n + 1, 0);
    for (const auto& t : mesh.triangles)
        for (const auto v : t) a.offset[v + 1] += 2;
    for (std::size_t v = 0; v < n; ++v) a.offset[v + 1] += a.offset[v];
    a.index.resize(a.offset[n]);
    std::vector<std::uint32_t> fill(a.offset.begin(), a.offset.end() - 1);
    for (const auto& t : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            a.index[fill[t[k]]++] = t[(k + 1) % 3];
            a.index[fill[t[k]]++] = t[(k + 2) % 3];
        }
    return a;
}

// Steps 3–4: from the strong vertices of each group whose peak excess reaches the shape floor,
// grow through connected vertices whose signed distance reaches grow_fraction of the group's
// peak distance (and the lower floor, and a share of the local tessellation tolerance): the
// region's extent is where the surface moved, not only where it moved beyond the tolerance.
// The grown extent is kept when its normal evidence reaches the normal floor's lower level:
// the normal field turns most on a damage's flanks, which the extent holds and the strong core
// of a smooth dent does not.
void grow(const Mesh& mesh, const DecisionEvidence& e, const std::vector<std::uint8_t>& missing,
          const std::vector<std::int32_t>& group, const std::vector<Group>& groups,
          const std::vector<float>& signed_distance, const std::vector<float>& signed_excess, const Floor& normal,
          const Floor& shape, double grow_fraction, std::vector<std::uint8_t>& damaged) {
    const std::size_t n = group.size();
    const Adjacency adj = adjacency(mesh);
    const bool have_tolerance = e.tolerance && e.tolerance->size() == n;
    std::vector<std::int32_t> visited(n, -1);
    std::vector<std::vector<std::uint32_t>> extent(groups.size());
    std::vector<float> extent_normal(groups.size(), 0.0f);
    std::vector<std::uint32_t> stack;
    for (std::size_t v = 0; v < n; ++v) {
        const auto g = group[v];
        if (g < 0 || signed_excess[v] < shape.value || visited[v] == g) continue;
        const auto gi = static_cast<std::size_t>(g);
        if (groups[gi].peak_excess < shape.value) continue;
        const double reach = std::max(grow_fraction * groups[gi].peak_distance, shape.low);
        stack.assign(1, static_cast<std::uint32_t>(v));
        visited[v] = g;
        while (!stack.empty()) {
            const std::uint32_t u = stack.back();
            stack.pop_back();
            extent[gi].push_back(u);
            extent_normal[gi] = std::max(extent_normal[gi], e.atlas->value_mean[u]);
            for (std::uint32_t i = adj.offset[u]; i < adj.offset[u + 1]; ++i) {
                const std::uint32_t w = adj.index[i];
                // A share of the local tessellation tolerance: where a coarse tessellation lies
                // systematically off a curved surface (a chord inside a convex part), the
                // offset is not a change of shape and must not carry a region along.
                const double tol = have_tolerance ? kGrowToleranceShare * (*e.tolerance)[w] : 0.0;
                if (visited[w] == g || !e.coverage->seen[w] || missing[w] || signed_distance[w] < std::max(reach, tol)) continue;
                visited[w] = g;
                stack.push_back(w);
            }
        }
    }
    for (std::size_t g = 0; g < groups.size(); ++g)
        if (extent_normal[g] >= normal.low)
            for (const auto u : extent[g]) damaged[u] = 1;
}

// Steps 2–4 for one sign of the shape change (+1 gain, −1 loss).
void one_sign(const Mesh& mesh, const DecisionEvidence& e, const std::vector<float>& excess,
              const std::vector<std::uint8_t>& missing, float sign, const Floor& normal, const Floor& shape,
              const DecisionOptions& o, std::vector<std::uint8_t>& damaged) {
    const std::size_t n = excess.size();
    std::vector<float> signed_excess(n), signed_distance(n);
    std::vector<std::uint8_t> candidate(n, 0);
    for (std::size_t v = 0; v < n; ++v) {
        signed_excess[v] = sign * excess[v];
        signed_distance[v] = sign * (*e.distance)[v];
        candidate[v] = e.coverage->seen[v] && !missing[v] && signed_excess[v] >= shape.low;
    }
    std::vector<std::int32_t> group;
    const std::size_t count = masked_components(mesh, candidate, group);
    std::vector<Group> groups(count);
    for (std::size_t v = 0; v < n; ++v) {
        if (group[v] < 0) continue;
        Group& g = groups[static_cast<std::size_t>(group[v])];
        g.peak_excess = std::max(g.peak_excess, signed_excess[v]);
        g.peak_distance = std::max(g.peak_distance, signed_distance[v]);
        g.max_normal = std::max(g.max_normal, e.atlas->value_mean[v]);
    }
    grow(mesh, e, missing, group, groups, signed_distance, signed_excess, normal, shape, o.grow_fraction, damaged);
}

}  // namespace

std::vector<std::uint8_t> fused_mask(const Mesh& reference, const DecisionEvidence& e, const std::vector<float>& excess,
                                     const Floor& normal, const Floor& shape, const DecisionOptions& o) {
    GLINT_ASSERT(e.distance && e.distance->size() == excess.size(), "fused rule without shape evidence");
    const std::size_t n = excess.size();
    std::vector<std::uint8_t> damaged(n, 0);
    const auto missing = missing_mask(e, excess, shape);
    one_sign(reference, e, excess, missing, -1.0f, normal, shape, o, damaged);
    one_sign(reference, e, excess, missing, +1.0f, normal, shape, o, damaged);
    // Step 5: missing surface counts as damage wherever the views saw the reference there
    // (its normal evidence is the metric's missing value, far above any floor).
    for (std::size_t v = 0; v < n; ++v)
        if (missing[v] && e.atlas->value_mean[v] >= normal.value) damaged[v] = 1;
    return damaged;
}

void describe_evidence(RegionResult& regions, const DecisionEvidence& e, const std::vector<float>& excess,
                       const Floor& normal, const Floor& shape) {
    std::vector<float> peak(regions.regions.size() + 1, 0.0f);
    for (std::size_t v = 0; v < excess.size(); ++v) {
        const auto id = static_cast<std::size_t>(regions.region_of_vertex[v]);
        if (id > 0 && std::abs(excess[v]) > std::abs(peak[id])) peak[id] = excess[v];
    }
    const MetricDescriptor& m = describe(e.metric);
    for (auto& r : regions.regions) {
        char text[256];
        if (r.kind == RegionKind::MissingSurface)
            std::snprintf(text, sizeof text, "no examined surface on %.0f%% of it; %s %.2f%s ≥ floor %.2f%s",
                          100.0 * r.missing_fraction, std::string(m.name).c_str(), r.max_value,
                          std::string(m.symbol).c_str(), normal.value, std::string(m.symbol).c_str());
        else
            std::snprintf(text, sizeof text, "shape change %+.3g beyond tessellation (floor %.3g) and %s %.2f%s (floor %.2f%s)",
                          static_cast<double>(peak[static_cast<std::size_t>(r.id)]), shape.value,
                          std::string(m.name).c_str(), r.max_value, std::string(m.symbol).c_str(), normal.value,
                          std::string(m.symbol).c_str());
        r.evidence = text;
    }
}

}  // namespace glint::detail
