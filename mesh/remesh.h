// Re-tessellation of a surface (CGAL's isotropic remeshing, behind a wall: no CGAL type here)
// and the other "same surface, other triangles" tools the real-data pairs are built with.
#pragma once

#include "mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace glint {

struct RemeshOptions {
    double target_edge = 1.0;  ///< mesh units, > 0
    int iterations = 3;        ///< split / collapse / flip / relax / project rounds, ≥ 1
};

/// Isotropic remeshing towards `target_edge`: every new or moved vertex is projected back onto
/// the input surface, so the result is the same surface with other triangles. Borders stay
/// borders. Normals are recomputed; colours, scalars and labels are dropped (they belonged to
/// the old vertices). \throw InputError an empty mesh, a non-positive edge, a mesh CGAL cannot
/// take as a polygon mesh (non-manifold), naming what was found.
[[nodiscard]] Mesh remesh_isotropic(const Mesh& mesh, const RemeshOptions& options);

/// Edge lengths of a mesh (each undirected edge once).
struct EdgeStats {
    double mean = 0.0;
    double median = 0.0;
    double min = 0.0;
    double max = 0.0;
    std::size_t edges = 0;
};
[[nodiscard]] EdgeStats edge_stats(const Mesh& mesh);

/// Shuffles vertex order and triangle order (and the corner order inside each triangle,
/// keeping orientation) with a seeded permutation; every per-vertex array follows.
void shuffle_mesh(Mesh& mesh, std::uint32_t seed);

}  // namespace glint
