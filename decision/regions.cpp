#include "decision/regions.h"

#include "mesh/components.h"
#include "mesh/error.h"

#include <algorithm>
#include <cmath>

namespace glint {

std::string to_string(RegionKind kind) {
    switch (kind) {
        case RegionKind::Dent: return "dent";
        case RegionKind::Bump: return "bump";
        case RegionKind::MissingSurface: return "missing surface";
    }
    return "?";
}

namespace {

// Marks as damaged every undamaged, seen group that touches only one damaged group, no
// unseen vertex and no mesh border, and is smaller (in vertices) than that group.
std::size_t fill_enclosed_holes(const Mesh& mesh, const std::vector<std::uint8_t>& seen,
                                std::vector<std::uint8_t>& damaged) {
    const std::size_t n = mesh.vertex_count();
    std::vector<std::int32_t> group, hole;
    const std::size_t groups = masked_components(mesh, damaged, group);
    std::vector<std::uint8_t> candidate(n);
    for (std::size_t v = 0; v < n; ++v) candidate[v] = !damaged[v] && seen[v];
    const std::size_t holes = masked_components(mesh, candidate, hole);
    constexpr std::int32_t kOpen = -2;  // touches several groups, an unseen vertex or a border
    std::vector<std::int32_t> neighbour(holes, -1);
    std::vector<std::size_t> hole_size(holes, 0), group_size(groups, 0);
    for (std::size_t v = 0; v < n; ++v) {
        if (hole[v] >= 0) ++hole_size[static_cast<std::size_t>(hole[v])];
        if (group[v] >= 0) ++group_size[static_cast<std::size_t>(group[v])];
    }
    auto touch = [&](std::int32_t h, std::int32_t other) {
        auto& nb = neighbour[static_cast<std::size_t>(h)];
        if (nb == kOpen) return;
        if (other < 0) nb = kOpen;  // an unseen vertex: not enclosed
        else if (nb == -1) nb = other;
        else if (nb != other) nb = kOpen;
    };
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const auto a = tri[k], b = tri[(k + 1) % 3];
            if (hole[a] >= 0 && hole[b] < 0) touch(hole[a], group[b]);
            if (hole[b] >= 0 && hole[a] < 0) touch(hole[b], group[a]);
        }
    const auto border = border_vertices(mesh);
    for (std::size_t v = 0; v < n; ++v)
        if (border[v] && hole[v] >= 0) neighbour[static_cast<std::size_t>(hole[v])] = kOpen;
    std::size_t filled = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (hole[v] < 0) continue;
        const auto h = static_cast<std::size_t>(hole[v]);
        const std::int32_t g = neighbour[h];
        if (g >= 0 && hole_size[h] < group_size[static_cast<std::size_t>(g)]) {
            damaged[v] = 1;
            ++filled;
        }
    }
    return filled;
}

struct Accumulated {
    Region r;
    double value_area = 0.0;
    double shape_area = 0.0;  // area with a known shape change
    double missing_area = 0.0;
    double best_value = -1.0;
    double gone_peak = 0.0;     // most negative depth of surface gone in a hole
    double gone_area = 0.0;     // area in a hole
    double loss_area = 0.0;     // area in a hole that is a loss (RegionFields::gone_loss)
    double counted_area = 0.0;  // area that meets RegionOptions::min_area
    Vec3d centroid_sum{0, 0, 0};
    std::vector<std::uint32_t> vertices;
};

void accumulate(Accumulated& g, const Mesh& mesh, std::size_t v, double area,
                const RegionFields& f) {
    const double value = (*f.value)[v];
    g.vertices.push_back(static_cast<std::uint32_t>(v));
    g.r.area += area;
    g.value_area += area * value;
    g.centroid_sum += area * mesh.positions[v].cast<double>();
    g.r.max_value = std::max(g.r.max_value, value);
    if (f.shape && std::isfinite((*f.shape)[v])) {
        const double d = (*f.shape)[v];
        if (std::abs(d) > std::abs(g.r.peak_depth)) g.r.peak_depth = d;
        g.r.volume += area * d;
        g.shape_area += area;
    }
    if (f.missing) g.missing_area += area * (*f.missing)[v];
    if (f.gone && std::isfinite((*f.gone)[v])) {
        g.gone_peak = std::min(g.gone_peak, static_cast<double>((*f.gone)[v]));
        g.gone_area += area;
        if (f.gone_loss && (*f.gone_loss)[v]) g.loss_area += area;
    }
    if (f.view && value > g.best_value) {
        g.best_value = value;
        g.r.best_view = (*f.view)[v];
    }
}

void finish(Accumulated& g, const RegionOptions& options, bool holes) {
    g.r.vertex_count = g.vertices.size();
    g.r.mean_value = g.r.area > 0 ? g.value_area / g.r.area : 0.0;
    g.r.mean_depth = g.shape_area > 0 ? g.r.volume / g.shape_area : 0.0;
    g.r.missing_fraction = g.r.area > 0 ? g.missing_area / g.r.area : 0.0;
    g.r.centroid = g.r.area > 0 ? Vec3d(g.centroid_sum / g.r.area) : Vec3d::Zero();
    // note: a region mostly without examined surface is a hole (decision/comparison.h); its
    // shape is the depth of the surface gone, negative where material was worn away or
    // removed: a loss. A hole of unknown direction stays "missing surface".
    // A region mostly in such a hole is that loss, also where the views saw the far side of an
    // open surface through the hole (its rim's distances point there, not at the loss).
    const bool hole = g.gone_area > 0 && (g.r.missing_fraction > options.missing_majority ||
                                          g.gone_area > options.missing_majority * g.r.area);
    g.r.hole = hole;
    if (hole && (g.gone_peak < 0 || g.loss_area > options.missing_majority * g.gone_area)) {
        g.r.kind = RegionKind::Dent;
        g.r.peak_depth = g.gone_peak;
    } else if (hole || g.r.missing_fraction > options.missing_majority)
        g.r.kind = RegionKind::MissingSurface;
    else if (holes && g.r.peak_depth == 0 && g.missing_area > 0)
        g.r.kind = RegionKind::MissingSurface;
    else g.r.kind = g.r.peak_depth < 0 ? RegionKind::Dent : RegionKind::Bump;
}

// The material gone with each surface-gone region (Region::is_hole_loss): the solid its
// surface bounds with the surface across its rim, by the divergence theorem as a sum of
// tetrahedra from the rim's centroid (exact where the rim is planar; a closed region's own
// centroid when it has no rim); each triangle weighs the share of its corners in the region.
// Positive for a surface wound outward. Σ area·depth would measure a long piece gone (a bone
// resected along its length) as its surface times half its length, not its volume.
std::vector<double> gone_volumes(const Mesh& mesh, const std::vector<Accumulated*>& regions) {
    const std::size_t n = mesh.vertex_count();
    std::vector<Vec3d> rim(regions.size(), Vec3d::Zero());
    std::vector<double> rim_count(regions.size(), 0.0), volume(regions.size(), 0.0);
    std::vector<std::int32_t> slot(n, -1), stamp(n, -1);
    for (std::size_t i = 0; i < regions.size(); ++i)
        for (const auto v : regions[i]->vertices) slot[v] = static_cast<std::int32_t>(i);
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::int32_t s = slot[tri[k]];
            if (s < 0) continue;
            for (std::size_t j = 1; j < 3; ++j) {
                const auto w = tri[(k + j) % 3];
                if (slot[w] == s || stamp[w] == s) continue;
                stamp[w] = s;
                rim[static_cast<std::size_t>(s)] += mesh.positions[w].cast<double>();
                rim_count[static_cast<std::size_t>(s)] += 1.0;
            }
        }
    std::vector<Vec3d> apex(regions.size());
    for (std::size_t i = 0; i < regions.size(); ++i)
        apex[i] = rim_count[i] > 0 ? Vec3d(rim[i] / rim_count[i]) : regions[i]->r.centroid;
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::int32_t s = slot[tri[k]];
            if (s < 0) continue;
            const Vec3d& c = apex[static_cast<std::size_t>(s)];
            const Vec3d a = mesh.positions[tri[0]].cast<double>() - c;
            const Vec3d b = mesh.positions[tri[1]].cast<double>() - c;
            const Vec3d d = mesh.positions[tri[2]].cast<double>() - c;
            volume[static_cast<std::size_t>(s)] += a.dot(b.cross(d)) / 18.0;  // ⅓ of a tetrahedron
        }
    return volume;
}

// RegionOptions::min_depth at the vertex of the group's peak shape change.
bool shallower_than_limit(const Accumulated& g, const RegionFields& f, const RegionOptions& o) {
    if (!o.min_depth || !f.shape || g.r.kind == RegionKind::MissingSurface) return false;
    float peak = 0.0f;
    std::uint32_t at = g.vertices.front();
    for (const auto v : g.vertices) {
        const float d = std::abs((*f.shape)[v]);
        if (std::isfinite(d) && d > peak) {
            peak = d;
            at = v;
        }
    }
    return peak < (*o.min_depth)[at];
}

}  // namespace

RegionResult find_regions(const Mesh& mesh, std::vector<std::uint8_t> damaged,
                          const std::vector<std::uint8_t>& seen, const RegionFields& fields,
                          const RegionOptions& options) {
    const std::size_t n = mesh.vertex_count();
    GLINT_ASSERT(fields.value && fields.value->size() == n, "value field does not match the mesh");
    GLINT_ASSERT(seen.size() == n && damaged.size() == n, "masks do not match the mesh");
    GLINT_ASSERT(!fields.shape || fields.shape->size() == n, "shape field does not match the mesh");
    RegionResult result;
    for (std::size_t v = 0; v < n; ++v) {
        damaged[v] = damaged[v] && seen[v];
        result.damaged_vertices += damaged[v];
    }
    if (options.fill_holes) result.filled_vertices = fill_enclosed_holes(mesh, seen, damaged);
    std::vector<std::int32_t> group;
    const std::size_t count = masked_components(mesh, damaged, group);
    const auto areas = vertex_areas(mesh);
    std::vector<Accumulated> groups(count);
    const auto* counted = options.min_area_counted;
    GLINT_ASSERT(!counted || counted->size() == n, "counted mask does not match the mesh");
    for (std::size_t v = 0; v < n; ++v) {
        if (group[v] < 0) continue;
        Accumulated& g = groups[static_cast<std::size_t>(group[v])];
        accumulate(g, mesh, v, areas[v], fields);
        if (!counted || (*counted)[v]) g.counted_area += areas[v];
    }
    std::vector<Accumulated*> kept;
    for (auto& g : groups) {
        if (g.vertices.size() < options.min_vertices || g.counted_area < options.min_area) {
            ++result.dropped_small;
            continue;
        }
        finish(g, options, fields.gone != nullptr);
        if (g.r.is_hole_loss() && g.counted_area < options.min_hole_area) {
            ++result.dropped_small;
            continue;
        }
        if (shallower_than_limit(g, fields, options)) {
            ++result.dropped_shallow;
            continue;
        }
        kept.push_back(&g);
    }
    // The volume of each surface gone: the solid, not the surface times its depth.
    std::vector<Accumulated*> gone;
    for (auto* g : kept)
        if (g->r.is_hole_loss()) gone.push_back(g);
    const std::vector<double> gone_volume = gone_volumes(mesh, gone);
    for (std::size_t i = 0; i < gone.size(); ++i)
        if (gone_volume[i] > 0) gone[i]->r.volume = -gone_volume[i];
    // Surface gone first (a resection, a fracture, worn-away material: the loss a reader
    // looks for), then by area.
    std::stable_sort(kept.begin(), kept.end(), [](const Accumulated* a, const Accumulated* b) {
        if (a->r.is_hole_loss() != b->r.is_hole_loss()) return a->r.is_hole_loss();
        return a->r.area > b->r.area;
    });
    result.region_of_vertex.assign(n, 0);
    for (std::size_t i = 0; i < kept.size(); ++i) {
        kept[i]->r.id = static_cast<std::int32_t>(i + 1);
        for (auto v : kept[i]->vertices) result.region_of_vertex[v] = kept[i]->r.id;
        result.regions.push_back(kept[i]->r);
    }
    return result;
}

}  // namespace glint
