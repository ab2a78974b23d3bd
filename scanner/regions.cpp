#include "scanner/regions.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace glint {

std::string to_string(RegionKind kind) { return kind == RegionKind::Dent ? "dent" : "bump"; }

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
        if (in.depth) {
            const double d = (*in.depth)[v];
            if (std::abs(d) > std::abs(g.r.max_depth)) g.r.max_depth = d;
        }
        if (in.distance) {
            const double d = (*in.distance)[v];
            if (std::abs(d) > std::abs(g.r.max_distance)) g.r.max_distance = d;
            g.signed_sum += a * d;
        } else if (in.depth) {
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
