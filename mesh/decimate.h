// Decimation for display: a mesh reduced to a triangle budget by quadric edge collapse
// (meshoptimizer's simplifier), with a set of triangles kept exactly as they are.
//
// Collapses merge vertices into vertices of the input, so every vertex of the result is one of
// the input's (original_vertex maps it back) and per-vertex values carry over unchanged. The
// mesh's own borders and the border between kept and decimated triangles do not move: the
// simplifier treats both as borders and locks their vertices.
#pragma once

#include "mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace glint {

struct DecimatedMesh {
    Mesh mesh;  ///< positions, triangles, normals (when the input had them)
    std::vector<std::uint32_t> original_vertex;  ///< per vertex of `mesh`: its id in the input
    double error = 0.0;                          ///< the simplifier's error estimate, mesh units
};

/// Triangles the simplifier works on at once (its working memory is ~60 bytes per triangle).
/// note: 250 000 rather than 500 000: report.html's decimation runs beside the atlas files'
/// writing (report/report.cpp), and with two pieces of 500 000 at a time a 2M-triangle run
/// peaked at 606 instead of 550 MiB; the page's mesh has a few more locked seams.
inline constexpr std::size_t kDecimatePiece = 250000;

/// The mesh with at most about `max_triangles` triangles (more when the kept triangles alone
/// exceed it, or when the error allowed, `max_error` mesh units, stops the collapses first).
/// keep[t] != 0: triangle t is kept as it is (empty: none). Larger meshes are simplified in
/// slabs of `piece` triangles along their longest axis, each with its borders locked, so the
/// seams keep their vertices. Scalars and labels are not carried (use original_vertex).
/// \pre keep empty or one entry per triangle; piece > 0.
[[nodiscard]] DecimatedMesh decimate(const Mesh& mesh, std::size_t max_triangles,
                                     const std::vector<std::uint8_t>& keep, double max_error,
                                     std::size_t piece = kDecimatePiece);

}  // namespace glint
