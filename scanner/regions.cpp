#include "scanner/regions.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace glint {

std::string to_string(RegionKind kind) { return kind == RegionKind::Dent ? "dent" : "bump"; }

namespace {

// Components (through edges) of vertices with mask[v] == value; returns the component id of
// every such vertex (-1 elsewhere) and the number of components.
std::size_t components_of(const Mesh& mesh, const std::vector<std::uint8_t>& mask, std::uint8_t value,
                          std::vector<std::int32_t>& id) {
    const std::size_t n = mesh.vertex_count();
    std::vector<std::uint32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const auto a = tri[k], b = tri[(k + 1) % 3];
            if (mask[a] == value && mask[b] == value) {
                const auto ra = find(a), rb = find(b);
                if (ra != rb) parent[ra] = rb;
            }
        }
    id.assign(n, -1);
    std::vector<std::int32_t> of_root(n, -1);
    std::size_t count = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (mask[v] != value) continue;
        const auto r = find(static_cast<std::uint32_t>(v));
        if (of_root[r] < 0) of_root[r] = static_cast<std::int32_t>(count++);
        id[v] = of_root[r];
    }
    return count;
}

// Marks as damaged every undamaged, seen group that touches only one damaged group, no
// unseen vertex and no mesh border, and is smaller (in vertices) than that group.
std::size_t fill_enclosed_holes(const Mesh& mesh, const std::vector<std::uint8_t>& seen,
                                std::vector<std::uint8_t>& damaged) {
    const std::size_t n = mesh.vertex_count();
    std::vector<std::int32_t> dgroup, hole;
    components_of(mesh, damaged, 1, dgroup);
    std::vector<std::uint8_t> candidate(n);
    for (std::size_t v = 0; v < n; ++v) candidate[v] = !damaged[v] && seen[v];
    const std::size_t holes = components_of(mesh, candidate, 1, hole);
    std::vector<std::int32_t> neighbour(holes, -1);  // the one damaged group it touches, -2 = several/open
    std::vector<std::size_t> hole_size(holes, 0), group_size;
    for (std::size_t v = 0; v < n; ++v) {
        if (hole[v] >= 0) ++hole_size[static_cast<std::size_t>(hole[v])];
        if (dgroup[v] >= 0) {
            if (group_size.size() <= static_cast<std::size_t>(dgroup[v])) group_size.resize(static_cast<std::size_t>(dgroup[v]) + 1, 0);
            ++group_size[static_cast<std::size_t>(dgroup[v])];
        }
    }
    auto touch = [&](std::int32_t h, std::int32_t other) {
        auto& nb = neighbour[static_cast<std::size_t>(h)];
        if (nb == -2) return;
        if (other < 0) nb = -2;             // unseen vertex: not enclosed
        else if (nb == -1) nb = other;
        else if (nb != other) nb = -2;      // touches two regions
    };
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const auto a = tri[k], b = tri[(k + 1) % 3];
            if (hole[a] >= 0 && hole[b] < 0) touch(hole[a], dgroup[b]);
            if (hole[b] >= 0 && hole[a] < 0) touch(hole[b], dgroup[a]);
        }
    // A hole on the mesh border is open, not enclosed.
    std::map<std::uint64_t, int> edge_use;
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const auto a = tri[k], b = tri[(k + 1) % 3];
            ++edge_use[(std::uint64_t{std::min(a, b)} << 32) | std::max(a, b)];
        }
    for (const auto& [key, uses] : edge_use) {
        if (uses != 1) continue;
        for (const auto v : {static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key & 0xFFFFFFFFu)})
            if (hole[v] >= 0) neighbour[static_cast<std::size_t>(hole[v])] = -2;
    }
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

}  // namespace

RegionResult find_regions(const Mesh& mesh, const RegionInputs& in, const RegionOptions& options) {
    const std::size_t n = mesh.vertex_count();
    GLINT_ASSERT(in.angle_deg && in.angle_deg->size() == n, "angle field does not match the mesh");
    GLINT_ASSERT(in.seen && in.seen->size() == n, "seen mask does not match the mesh");
    const auto& angle = *in.angle_deg;
    const auto& seen = *in.seen;
    std::vector<std::uint8_t> damaged(n, 0);
    RegionResult result;
    for (std::size_t v = 0; v < n; ++v) {
        damaged[v] = seen[v] && angle[v] >= options.threshold_deg;
        result.damaged_vertices += damaged[v];
    }
    if (options.fill_holes) result.filled_vertices = fill_enclosed_holes(mesh, seen, damaged);
    // Union-find over edges whose both ends are damaged.
    std::vector<std::uint32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const auto a = tri[k];
            const auto b = tri[(k + 1) % 3];
            if (damaged[a] && damaged[b]) {
                const auto ra = find(a);
                const auto rb = find(b);
                if (ra != rb) parent[ra] = rb;
            }
        }
    const auto areas = vertex_areas(mesh);
    struct Acc {
        Region r;
        double angle_area = 0.0;
        double signed_sum = 0.0;
        double best_angle = -1.0;
        Vec3d centroid_sum{0, 0, 0};
        std::vector<std::uint32_t> vertices;
    };
    std::vector<std::int32_t> group_of_root(n, -1);
    std::vector<Acc> groups;
    for (std::size_t v = 0; v < n; ++v) {
        if (!damaged[v]) continue;
        const auto root = find(static_cast<std::uint32_t>(v));
        if (group_of_root[root] < 0) {
            group_of_root[root] = static_cast<std::int32_t>(groups.size());
            groups.emplace_back();
        }
        Acc& g = groups[static_cast<std::size_t>(group_of_root[root])];
        const double a = areas[v];
        g.vertices.push_back(static_cast<std::uint32_t>(v));
        g.r.area += a;
        g.angle_area += a * angle[v];
        g.centroid_sum += a * mesh.positions[v].cast<double>();
        if (angle[v] > g.r.max_angle_deg) g.r.max_angle_deg = angle[v];
        if (in.depth && std::isfinite((*in.depth)[v])) {
            const double d = (*in.depth)[v];
            if (std::abs(d) > std::abs(g.r.max_depth)) g.r.max_depth = d;
        }
        if (in.distance) {
            const double d = (*in.distance)[v];
            if (std::abs(d) > std::abs(g.r.max_distance)) g.r.max_distance = d;
            g.signed_sum += a * d;
        } else if (in.depth && std::isfinite((*in.depth)[v])) {
            g.signed_sum += a * (*in.depth)[v];
        }
        if (in.view && angle[v] > g.best_angle) {
            g.best_angle = angle[v];
            g.r.best_view = (*in.view)[v];
        }
    }
    std::vector<Acc*> kept;
    for (auto& g : groups) {
        if (g.vertices.size() < options.min_vertices) {
            ++result.dropped_small;
            continue;
        }
        g.r.vertex_count = g.vertices.size();
        g.r.mean_angle_deg = g.r.area > 0 ? g.angle_area / g.r.area : 0.0;
        g.r.centroid = g.r.area > 0 ? Vec3d(g.centroid_sum / g.r.area) : Vec3d::Zero();
        g.r.kind = g.signed_sum < 0 ? RegionKind::Dent : RegionKind::Bump;
        kept.push_back(&g);
    }
    std::stable_sort(kept.begin(), kept.end(), [](const Acc* a, const Acc* b) { return a->r.area > b->r.area; });
    result.region_of_vertex.assign(n, 0);
    for (std::size_t i = 0; i < kept.size(); ++i) {
        kept[i]->r.id = static_cast<std::int32_t>(i + 1);
        for (auto v : kept[i]->vertices) result.region_of_vertex[v] = kept[i]->r.id;
        result.regions.push_back(kept[i]->r);
    }
    return result;
}

}  // namespace glint
