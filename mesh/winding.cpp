#include "mesh/winding.h"

#include "mesh/normals.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace glint {

double outward_score(const Mesh& mesh) {
    Vec3d origin = Vec3d::Zero();
    double area = 0.0;
    std::vector<Vec3d> centre(mesh.triangles.size()), normal_area(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const Vec3d a = mesh.positions[tri[0]].cast<double>(),
                    b = mesh.positions[tri[1]].cast<double>(),
                    c = mesh.positions[tri[2]].cast<double>();
        normal_area[t] = 0.5 * (b - a).cross(c - a);  // unit normal × area
        centre[t] = (a + b + c) / 3.0;
        const double at = normal_area[t].norm();
        origin += at * centre[t];
        area += at;
    }
    if (!(area > 0.0)) return 0.0;
    origin /= area;
    double flux = 0.0, spread = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Vec3d r = centre[t] - origin;
        flux += normal_area[t].dot(r);
        spread += normal_area[t].norm() * r.norm();
    }
    return spread > 0.0 ? flux / spread : 0.0;
}

bool is_closed(const Mesh& mesh) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(3 * mesh.triangles.size());
    for (const auto& tri : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = tri[static_cast<std::size_t>(k)];
            const std::uint32_t b = tri[static_cast<std::size_t>((k + 1) % 3)];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        if (j - i != 2) return false;
        i = j;
    }
    return !edges.empty();
}

void reverse_winding(Mesh& mesh) {
    for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
    compute_vertex_normals(mesh);
}

}  // namespace glint
