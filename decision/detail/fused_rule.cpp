// The fused rule: a region needs both a change of shape and a change of the normal field.
// See decision/decision.h for the rule; the reasons for each step are here.
#include "decision/detail/fused_rule.h"

#include "mesh/components.h"
#include "mesh/error.h"
#include "mesh/units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glint::detail {

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

namespace {

// A vertex whose examined surface is missing: most observations found none behind it, or its
// closest examined point lies on a border of the examined mesh while the distance is beyond
// the shape floor (a hole or a cut edge, not a surface that moved).
// note: 0.5 — the majority of the observation weight, the same rule as RegionOptions.
std::vector<std::uint8_t> missing_mask(const DecisionEvidence& e, const std::vector<float>& excess,
                                       const Floor& shape) {
    const std::size_t n = excess.size();
    std::vector<std::uint8_t> m(n, 0);
    for (std::size_t v = 0; v < n; ++v) {
        if (!e.coverage->seen[v]) continue;
        const bool border = e.at_border && (*e.at_border)[v] && std::abs(excess[v]) >= shape.value;
        m[v] = e.atlas->missing[v] > 0.5f || border;
    }
    return m;
}

// note: half the tolerance (kTessellationTolerance·h·θ, smoothed over the 1-ring). On the jaw
// remeshed at 1.2× with its condyle flattened, the coarse examined mesh cuts the flat top's
// crease and lies 0.07–0.1 mm off the untouched surface below it, where ½·h·θ is ~0.22 mm;
// without the gate that band joins the region (precision 0.81 instead of 0.96).
constexpr double kGrowToleranceShare = 0.5;

// note: the gate never asks more than 1.5 reaches (15 % of the peak): a vertex that moved by
// that much is part of the change whatever the local tolerance. On the jaw remeshed at 1.2×
// the faceted ramus turns its vertex normals by 15–22° from the faces around them, so ½·h·θ
// reaches 0.05–0.12 mm inside a broad 0.2 mm dent and the gate alone cut the region to half
// its extent (recall 0.50). With the ceiling at 1.2–1.6 reaches every real-data damage pair
// keeps F1 ≥ 0.9 (ramus at 1.2× 0.94, condyle flattening at 1.2× 0.93); at 1.0 the flattening
// falls to 0.89, at 1.8 the ramus to 0.89.
constexpr double kGateCeilingInReaches = 1.5;

// How far an extent grows: a vertex joins when its signed distance reaches `level` and, below
// `ceiling`, half its local tessellation tolerance.
struct Reach {
    double level = 0.0;
    double ceiling = 0.0;
};

struct Group {
    float peak_excess = 0.0f;    // largest signed excess magnitude (in the group's sign)
    float peak_distance = 0.0f;  // largest signed distance magnitude
    float max_normal = 0.0f;
};

// What both signs' growth reads of the mesh: its adjacency and the smoothed tessellation
// tolerance, built once per zoom.
struct Neighbourhood {
    Adjacency adjacency;
    std::vector<float> tolerance;  // smoothed tessellation tolerance (empty: none measured)
};

// The median over each vertex's closed 1-ring: the tolerance's sharpness term flickers from
// vertex to vertex on an irregular tessellation; a crease keeps it high all along.
std::vector<float> smoothed_tolerance(const Adjacency& adj, const std::vector<float>& t) {
    std::vector<float> out(t.size());
    std::vector<float> ring;
    for (std::size_t v = 0; v < t.size(); ++v) {
        ring.assign(1, t[v]);
        for (std::uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i)
            ring.push_back(t[adj.index[i]]);
        const auto mid = ring.begin() + static_cast<std::ptrdiff_t>(ring.size() / 2);
        std::nth_element(ring.begin(), mid, ring.end());
        out[v] = *mid;
    }
    return out;
}

Neighbourhood neighbourhood(const Mesh& mesh, const DecisionEvidence& e) {
    Neighbourhood n{adjacency(mesh), {}};
    if (e.tolerance && e.tolerance->size() == mesh.vertex_count())
        n.tolerance = smoothed_tolerance(n.adjacency, *e.tolerance);
    return n;
}

// One extent grown through the distance field (step 3).
struct Extent {
    Reach reach;              // how far it grew
    float max_normal = 0.0f;  // largest normal evidence inside
    std::vector<std::uint32_t> vertices;
};

class Grower {
  public:
    Grower(const Neighbourhood& near, const DecisionEvidence& e,
           const std::vector<std::uint8_t>& missing, const std::vector<float>& signed_distance)
        : adj_(near.adjacency),
          tolerance_(near.tolerance),
          e_(e),
          missing_(missing),
          distance_(signed_distance),
          owner_(signed_distance.size(), -1),
          stamp_(signed_distance.size(), -1) {}

    // Grows from `seeds` with `reach`. Returns the extent it touched that was grown before
    // (a stronger one, the caller merges), or -1 with the vertices in `out`.
    std::int32_t grow(const std::vector<std::uint32_t>& seeds, const Reach& reach, std::int32_t id,
                      Extent& out) {
        ++pass_;
        std::vector<std::uint32_t> stack;
        for (const auto s : seeds) {
            if (distance_[s] < reach.level || stamp_[s] == pass_ || owner_[s] == id) continue;
            if (owner_[s] >= 0) return owner_[s];
            stamp_[s] = pass_;
            stack.push_back(s);
        }
        out.vertices.clear();
        while (!stack.empty()) {
            const std::uint32_t u = stack.back();
            stack.pop_back();
            out.vertices.push_back(u);
            for (std::uint32_t i = adj_.offset[u]; i < adj_.offset[u + 1]; ++i) {
                const std::uint32_t w = adj_.index[i];
                if (stamp_[w] == pass_ || owner_[w] == id || !e_.coverage->seen[w] || missing_[w] ||
                    distance_[w] < gate(w, reach))
                    continue;
                if (owner_[w] >= 0) return owner_[w];
                stamp_[w] = pass_;
                stack.push_back(w);
            }
        }
        return -1;
    }

    void claim(const Extent& x, std::int32_t id) {
        for (const auto u : x.vertices) owner_[u] = id;
    }

  private:
    // A share of the local tessellation tolerance: where a coarse tessellation lies
    // systematically off a curved surface (a chord across a crease), the offset is not a change
    // of shape and must not carry a region along.
    double gate(std::uint32_t w, const Reach& reach) const {
        const double tolerance = tolerance_.empty() ? 0.0 : kGrowToleranceShare * tolerance_[w];
        return std::max(reach.level, std::min(tolerance, reach.ceiling));
    }

    const Adjacency& adj_;
    const std::vector<float>& tolerance_;  // smoothed tessellation tolerance (empty: none)
    const DecisionEvidence& e_;
    const std::vector<std::uint8_t>& missing_;
    const std::vector<float>& distance_;
    std::vector<std::int32_t> owner_;  // extent a vertex belongs to
    std::vector<std::int32_t> stamp_;  // pass that visited a vertex
    std::int32_t pass_ = 0;
};

// Steps 3–4: from the strong vertices of each group whose peak excess reaches the shape floor,
// grow through connected vertices whose signed distance reaches grow_fraction of the group's
// peak distance (and the lower floor, and — below 1.5 times that reach — half the local
// tessellation tolerance): the region's extent is where the surface moved, not only where it
// moved beyond the tolerance.
// Groups grow strongest first; a weaker group that runs into a stronger extent is a fragment of
// the same change (a rough floor splits one damage into several groups) and joins it under the
// stronger reach, so its shallow fringe does not ride in on its own small peak.
// An extent is kept when its normal evidence reaches the normal floor's lower level: the
// normal field turns most on a damage's flanks, which the extent holds and the strong core of
// a smooth dent does not.
void grow(const Neighbourhood& near, const DecisionEvidence& e,
          const std::vector<std::uint8_t>& missing, const std::vector<std::int32_t>& group,
          const std::vector<Group>& groups, const std::vector<float>& signed_distance,
          const std::vector<float>& signed_excess, const Floor& normal, const Floor& shape,
          double grow_fraction, std::vector<std::uint8_t>& damaged) {
    std::vector<std::vector<std::uint32_t>> seeds(groups.size());
    for (std::size_t v = 0; v < group.size(); ++v)
        if (group[v] >= 0 && signed_excess[v] >= shape.value)
            seeds[static_cast<std::size_t>(group[v])].push_back(static_cast<std::uint32_t>(v));
    std::vector<std::size_t> order;
    for (std::size_t g = 0; g < groups.size(); ++g)
        if (groups[g].peak_excess >= shape.value && !seeds[g].empty()) order.push_back(g);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return groups[a].peak_distance > groups[b].peak_distance;
    });
    Grower grower(near, e, missing, signed_distance);
    std::vector<Extent> extents;
    Extent x;
    for (const auto g : order) {
        const auto id = static_cast<std::int32_t>(extents.size());
        const double level = grow_fraction * groups[g].peak_distance;
        const Reach reach{std::max(level, shape.low), kGateCeilingInReaches * level};
        std::int32_t into = grower.grow(seeds[g], reach, id, x);
        if (into >= 0) {
            // note: grown again under the stronger extent's reach; what it reaches is added.
            const auto target = static_cast<std::size_t>(into);
            grower.grow(seeds[g], extents[target].reach, into, x);
            grower.claim(x, into);
            for (const auto u : x.vertices) extents[target].vertices.push_back(u);
            continue;
        }
        x.reach = reach;
        grower.claim(x, id);
        extents.push_back(std::move(x));
        x = Extent{};
    }
    for (auto& ex : extents) {
        for (const auto u : ex.vertices)
            ex.max_normal = std::max(ex.max_normal, e.atlas->value_mean[u]);
        if (!normal.corroborates || ex.max_normal >= normal.low)
            for (const auto u : ex.vertices) damaged[u] = 1;
    }
}

// Steps 2–4 for one sign of the shape change (+1 gain, −1 loss).
void one_sign(const Mesh& mesh, const Neighbourhood& near, const DecisionEvidence& e,
              const std::vector<float>& excess, const std::vector<std::uint8_t>& missing,
              float sign, const Floor& normal, const Floor& shape, const DecisionOptions& o,
              std::vector<std::uint8_t>& damaged) {
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
    grow(near, e, missing, group, groups, signed_distance, signed_excess, normal, shape,
         o.grow_fraction, damaged);
}

}  // namespace

std::vector<std::uint8_t> fused_mask(const Mesh& reference, const DecisionEvidence& e,
                                     const std::vector<float>& excess, const Floor& normal,
                                     const Floor& shape, const DecisionOptions& o) {
    GLINT_ASSERT(e.distance && e.distance->size() == excess.size(),
                 "fused rule without shape evidence");
    const std::size_t n = excess.size();
    std::vector<std::uint8_t> damaged(n, 0);
    const auto missing = missing_mask(e, excess, shape);
    const Neighbourhood near = neighbourhood(reference, e);
    one_sign(reference, near, e, excess, missing, -1.0f, normal, shape, o, damaged);
    one_sign(reference, near, e, excess, missing, +1.0f, normal, shape, o, damaged);
    // Step 5: missing surface counts as damage wherever the views saw the reference there
    // (its normal evidence is the metric's missing value, far above any floor).
    // Not where the normal field cannot tell (Floor::corroborates): the missing value is its
    // evidence, and surface the other side lacks by nature is no change of this one.
    if (normal.corroborates)
        for (std::size_t v = 0; v < n; ++v)
            if (missing[v] && e.atlas->value_mean[v] >= normal.value) damaged[v] = 1;
    return damaged;
}

void describe_evidence(RegionResult& regions, const DecisionEvidence& e,
                       const std::vector<float>& excess, const Floor& normal, const Floor& shape) {
    std::vector<float> peak(regions.regions.size() + 1, 0.0f);
    for (std::size_t v = 0; v < excess.size(); ++v) {
        const auto id = static_cast<std::size_t>(regions.region_of_vertex[v]);
        if (id > 0 && std::abs(excess[v]) > std::abs(peak[id])) peak[id] = excess[v];
    }
    const MetricDescriptor& m = describe(e.metric);
    for (auto& r : regions.regions) {
        char text[400];
        if (r.is_hole_loss())
            std::snprintf(text, sizeof text,
                          "surface gone: no examined surface on %.0f%% of it, a hole the examined "
                          "scan covers around; a loss at least as deep as the reference stood "
                          "above the hole's rim (%s); %s %.2f%s ≥ floor %.2f%s",
                          100.0 * r.missing_fraction,
                          with_unit(-r.peak_depth, e.unit, 1, "%.3g").c_str(),
                          std::string(m.name).c_str(), r.max_value, std::string(m.symbol).c_str(),
                          normal.value, std::string(m.symbol).c_str());
        else if (r.kind == RegionKind::MissingSurface)
            std::snprintf(
                text, sizeof text, "no examined surface on %.0f%% of it; %s %.2f%s ≥ floor %.2f%s",
                100.0 * r.missing_fraction, std::string(m.name).c_str(), r.max_value,
                std::string(m.symbol).c_str(), normal.value, std::string(m.symbol).c_str());
        else
            std::snprintf(
                text, sizeof text,
                "shape change %s beyond tessellation (floor %s) and %s %.2f%s (floor %.2f%s)",
                with_unit(peak[static_cast<std::size_t>(r.id)], e.unit, 1, "%+.3g").c_str(),
                with_unit(shape.value, e.unit, 1, "%.3g").c_str(), std::string(m.name).c_str(),
                r.max_value, std::string(m.symbol).c_str(), normal.value,
                std::string(m.symbol).c_str());
        r.evidence = text;
    }
}

}  // namespace glint::detail
