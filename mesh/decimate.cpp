#include "mesh/decimate.h"

#include "mesh/error.h"

#include <meshoptimizer.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

namespace glint {

namespace {

// `indices` (triangles, 3 per) simplified to `share` of their count, piece by piece; `error`:
// the largest error estimate of a piece, mesh units. note: meshoptimizer's simplifier holds
// ~60 bytes per triangle of working memory (a 2M-triangle atlas in one piece: 120 MB).
// Triangles are ordered along the mesh's longest axis so a piece is one slab of the surface;
// each piece keeps its borders (LockBorder), so the seams keep their vertices and still join.
std::vector<unsigned> simplify_in_pieces(const Mesh& mesh, std::vector<unsigned> indices,
                                         double share, double max_error,
                                         std::size_t piece_triangles, double& error) {
    const std::size_t count = indices.size() / 3;
    const std::size_t pieces = (count + piece_triangles - 1) / piece_triangles;
    if (pieces > 1) {
        const Bounds b = bounds(mesh);
        const Vec3f extent = b.extent();
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (extent[a] > extent[axis]) axis = a;
        std::vector<std::uint32_t> order(count);
        std::vector<float> key(count);
        for (std::size_t t = 0; t < count; ++t) {
            order[t] = static_cast<std::uint32_t>(t);
            key[t] = mesh.positions[indices[3 * t]][axis] +
                     mesh.positions[indices[3 * t + 1]][axis] +
                     mesh.positions[indices[3 * t + 2]][axis];
        }
        // Only the slabs matter, not the order inside one: each piece boundary is placed by a
        // partition (nth_element), O(n) per boundary instead of a sort of every triangle.
        const auto by_key = [&](std::uint32_t x, std::uint32_t y) { return key[x] < key[y]; };
        for (std::size_t p = 1; p < pieces; ++p)
            std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(count * (p - 1) / pieces),
                             order.begin() + static_cast<std::ptrdiff_t>(count * p / pieces),
                             order.end(), by_key);
        std::vector<unsigned> sorted(indices.size());
        for (std::size_t t = 0; t < count; ++t)
            std::copy_n(&indices[3 * order[t]], 3, &sorted[3 * t]);
        indices = std::move(sorted);
    }
    // The pieces are independent (each keeps its borders): simplified on every worker, joined
    // in order. Each piece hands the simplifier only its own vertices, renumbered: its working
    // memory is per vertex it is given as well as per triangle (a 2M-triangle atlas in four
    // pieces held 88 MB per piece with the whole mesh's vertices, two pieces at a time).
    std::vector<std::vector<unsigned>> simplified(pieces);
    std::vector<double> errors(pieces, 0.0);
    tbb::parallel_for(std::size_t{0}, pieces, [&](std::size_t p) {
        const std::size_t first = count * p / pieces, last = count * (p + 1) / pieces;
        const std::size_t n = 3 * (last - first);
        std::vector<unsigned> local(&indices[3 * first], &indices[3 * first] + n);
        std::vector<unsigned> global = local;  // local id → mesh vertex
        std::sort(global.begin(), global.end());
        global.erase(std::unique(global.begin(), global.end()), global.end());
        std::vector<Vec3f> xyz(global.size());
        for (std::size_t k = 0; k < global.size(); ++k) xyz[k] = mesh.positions[global[k]];
        for (auto& v : local)
            v = static_cast<unsigned>(std::lower_bound(global.begin(), global.end(), v) -
                                      global.begin());
        const float* coords = reinterpret_cast<const float*>(xyz.data());
        // The simplifier measures its error relative to the extent of the vertices it is given.
        const float scale = meshopt_simplifyScale(coords, xyz.size(), sizeof(Vec3f));
        auto& piece = simplified[p];
        piece.resize(n);
        const auto target = static_cast<std::size_t>(share * static_cast<double>(last - first));
        float piece_error = 0.0f;
        piece.resize(meshopt_simplify(
            piece.data(), local.data(), n, coords, xyz.size(), sizeof(Vec3f), 3 * target,
            static_cast<float>(max_error / scale), meshopt_SimplifyLockBorder, &piece_error));
        for (auto& v : piece) v = global[v];
        errors[p] = static_cast<double>(piece_error) * static_cast<double>(scale);
    });
    std::vector<unsigned> out;
    for (std::size_t p = 0; p < pieces; ++p) {
        out.insert(out.end(), simplified[p].begin(), simplified[p].end());
        error = std::max(error, errors[p]);
    }
    return out;
}

}  // namespace

DecimatedMesh decimate(const Mesh& mesh, std::size_t max_triangles,
                       const std::vector<std::uint8_t>& keep, double max_error, std::size_t piece) {
    GLINT_ASSERT(keep.empty() || keep.size() == mesh.triangle_count(),
                 "decimate: one keep flag per triangle");
    GLINT_ASSERT(piece > 0, "decimate: pieces of at least one triangle");
    std::vector<unsigned> kept, rest;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        auto& into = !keep.empty() && keep[t] ? kept : rest;
        into.insert(into.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
    }
    DecimatedMesh out;
    const std::size_t budget =
        max_triangles > kept.size() / 3 ? max_triangles - kept.size() / 3 : 0;
    if (3 * budget < rest.size() && !rest.empty()) {
        // note: the target is never below one triangle in 64 of the rest, so a tiny budget
        // does not collapse the surface into a few large triangles.
        const double share = static_cast<double>(std::max(budget, rest.size() / 3 / 64)) /
                             static_cast<double>(rest.size() / 3);
        rest = simplify_in_pieces(mesh, std::move(rest), share, max_error, piece, out.error);
    }
    // The vertices the triangles use, renumbered in order of first use.
    std::vector<std::uint32_t> remap(mesh.vertex_count(),
                                     std::numeric_limits<std::uint32_t>::max());
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
