#include "mesh/normals.h"

#include <algorithm>
#include <cmath>

namespace glint {

void compute_vertex_normals(Mesh& mesh) {
    // Accumulate in double: at 1M+ triangles float sums lose the last digits that the
    // tessellation-independence tests look at.
    std::vector<Vec3d> sum(mesh.positions.size(), Vec3d::Zero());
    for (const auto& tri : mesh.triangles) {
        const Vec3d p[3] = {mesh.positions[tri[0]].cast<double>(),
                            mesh.positions[tri[1]].cast<double>(),
                            mesh.positions[tri[2]].cast<double>()};
        const Vec3d n = (p[1] - p[0]).cross(p[2] - p[0]);
        const double len = n.norm();
        if (!(len > 0.0)) continue;
        const Vec3d unit = n / len;
        for (int k = 0; k < 3; ++k) {
            const Vec3d e1 = p[(k + 1) % 3] - p[k];
            const Vec3d e2 = p[(k + 2) % 3] - p[k];
            // Interior angle at corner k by atan2(|e1×e2|, e1·e2): accurate for small and
            // obtuse angles alike, unlike acos of the normalised dot product.
            const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
            sum[tri[static_cast<std::size_t>(k)]] += angle * unit;
        }
    }
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t v = 0; v < sum.size(); ++v) {
        const double len = sum[v].norm();
        mesh.normals[v] = len > 0.0 ? Vec3f((sum[v] / len).cast<float>()) : Vec3f::Zero();
    }
}

}  // namespace glint
