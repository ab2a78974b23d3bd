#include "mesh/remesh.h"

#include "mesh/error.h"
#include "mesh/normals.h"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <unordered_map>

namespace glint {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
namespace pmp = CGAL::Polygon_mesh_processing;

SurfaceMesh to_surface_mesh(const Mesh& mesh) {
    std::vector<Point> points;
    points.reserve(mesh.vertex_count());
    for (const auto& p : mesh.positions) points.emplace_back(p.x(), p.y(), p.z());
    std::vector<std::vector<std::size_t>> polygons;
    polygons.reserve(mesh.triangle_count());
    for (const auto& t : mesh.triangles) polygons.push_back({t[0], t[1], t[2]});
    if (!pmp::is_polygon_soup_a_polygon_mesh(polygons))
        throw InputError(
            "remesh: the mesh is not an oriented 2-manifold (non-manifold edges or vertices, or "
            "inconsistent orientation); expected a manifold surface");
    SurfaceMesh out;
    pmp::polygon_soup_to_polygon_mesh(points, polygons, out);
    return out;
}

Mesh from_surface_mesh(const SurfaceMesh& sm) {
    Mesh out;
    std::unordered_map<SurfaceMesh::Vertex_index, std::uint32_t> id;
    id.reserve(sm.number_of_vertices());
    for (const auto v : sm.vertices()) {
        const Point& p = sm.point(v);
        id.emplace(v, static_cast<std::uint32_t>(out.positions.size()));
        out.positions.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                   static_cast<float>(p.z()));
    }
    for (const auto f : sm.faces()) {
        Triangle t{};
        int k = 0;
        for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
            if (k == 3) throw InputError("remesh: CGAL returned a face with more than 3 corners");
            t[static_cast<std::size_t>(k++)] = id.at(v);
        }
        out.triangles.push_back(t);
    }
    return out;
}

}  // namespace

Mesh remesh_isotropic(const Mesh& mesh, const RemeshOptions& options) {
    if (mesh.triangle_count() == 0) throw InputError("remesh: empty mesh (0 triangles)");
    if (!(options.target_edge > 0.0))
        throw InputError("remesh: target edge " + std::to_string(options.target_edge) +
                         ", expected > 0");
    if (options.iterations < 1)
        throw InputError("remesh: iterations " + std::to_string(options.iterations) +
                         ", expected ≥ 1");
    SurfaceMesh sm = to_surface_mesh(mesh);
    pmp::isotropic_remeshing(
        faces(sm), options.target_edge, sm,
        pmp::parameters::number_of_iterations(static_cast<unsigned>(options.iterations))
            .number_of_relaxation_steps(3));
    sm.collect_garbage();
    Mesh out = from_surface_mesh(sm);
    out.unit = mesh.unit;
    compute_vertex_normals(out);
    return out;
}

EdgeStats edge_stats(const Mesh& mesh) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(mesh.triangle_count() * 3);
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = t[static_cast<std::size_t>(k)],
                                b = t[static_cast<std::size_t>((k + 1) % 3)];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    EdgeStats s;
    s.edges = edges.size();
    if (edges.empty()) return s;
    std::vector<double> lengths;
    lengths.reserve(edges.size());
    for (const auto& [a, b] : edges)
        lengths.push_back(static_cast<double>((mesh.positions[a] - mesh.positions[b]).norm()));
    s.mean =
        std::accumulate(lengths.begin(), lengths.end(), 0.0) / static_cast<double>(lengths.size());
    const auto [lo, hi] = std::minmax_element(lengths.begin(), lengths.end());
    s.min = *lo;
    s.max = *hi;
    auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
    std::nth_element(lengths.begin(), mid, lengths.end());
    s.median = *mid;
    return s;
}

void shuffle_mesh(Mesh& mesh, std::uint32_t seed) {
    std::mt19937 rng(seed);
    const std::size_t n = mesh.vertex_count();
    std::vector<std::uint32_t> order(n);  // order[new] = old
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<std::uint32_t> new_id(n);
    for (std::size_t i = 0; i < n; ++i) new_id[order[i]] = static_cast<std::uint32_t>(i);
    auto permute = [&](auto& values) {
        if (values.size() != n) return;
        auto copy = values;
        for (std::size_t i = 0; i < n; ++i) values[i] = copy[order[i]];
    };
    permute(mesh.positions);
    permute(mesh.normals);
    permute(mesh.colors);
    permute(mesh.labels);
    for (auto& s : mesh.scalars) permute(s.values);
    std::uniform_int_distribution<int> rotate(0, 2);
    for (auto& t : mesh.triangles) {
        for (auto& v : t) v = new_id[v];
        std::rotate(t.begin(), t.begin() + rotate(rng), t.end());  // same orientation
    }
    std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), rng);
}

}  // namespace glint
