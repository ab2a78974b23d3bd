#include "mesh/decimate.h"

#include "mesh/error.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <limits>

namespace glint {

DecimatedMesh decimate(const Mesh& mesh, std::size_t max_triangles, const std::vector<std::uint8_t>& keep,
                       double max_error) {
    GLINT_ASSERT(keep.empty() || keep.size() == mesh.triangle_count(), "decimate: one keep flag per triangle");
    std::vector<unsigned> kept, rest;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        auto& into = !keep.empty() && keep[t] ? kept : rest;
        into.insert(into.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
    }
    DecimatedMesh out;
    const std::size_t budget = max_triangles > kept.size() / 3 ? max_triangles - kept.size() / 3 : 0;
    if (3 * budget < rest.size() && !rest.empty()) {
        const auto* xyz = reinterpret_cast<const float*>(mesh.positions.data());
        const float scale = meshopt_simplifyScale(xyz, mesh.vertex_count(), sizeof(Vec3f));
        std::vector<unsigned> simplified(rest.size());
        float error = 0.0f;
        // note: the target is never below one triangle in 64 of the rest, so a tiny budget
        // does not collapse the surface into a few large triangles.
        const std::size_t target = 3 * std::max(budget, rest.size() / 3 / 64);
        simplified.resize(meshopt_simplify(simplified.data(), rest.data(), rest.size(), xyz, mesh.vertex_count(),
                                           sizeof(Vec3f), target, static_cast<float>(max_error / scale),
                                           meshopt_SimplifyLockBorder, &error));
        rest = std::move(simplified);
        out.error = static_cast<double>(error) * static_cast<double>(scale);
    }
    // The vertices the triangles use, renumbered in order of first use.
    std::vector<std::uint32_t> remap(mesh.vertex_count(), std::numeric_limits<std::uint32_t>::max());
    const bool normals = mesh.has_normals();
    for (const auto* part : {&kept, &rest})
        for (std::size_t i = 0; i < part->size(); i += 3) {
            Triangle t{};
            for (std::size_t k = 0; k < 3; ++k) {
                const unsigned v = (*part)[i + k];
                if (remap[v] == std::numeric_limits<std::uint32_t>::max()) {
                    remap[v] = static_cast<std::uint32_t>(out.original_vertex.size());
                    out.original_vertex.push_back(v);
                    out.mesh.positions.push_back(mesh.positions[v]);
                    if (normals) out.mesh.normals.push_back(mesh.normals[v]);
                }
                t[k] = remap[v];
            }
            out.mesh.triangles.push_back(t);
        }
    out.mesh.unit = mesh.unit;
    return out;
}

}  // namespace glint
