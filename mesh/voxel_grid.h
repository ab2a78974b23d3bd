// The voxel grid a mesh file was extracted on, read from its vertices alone (issue 50): a
// surface exported from a CT segmentation as STL/PLY/OBJ without smoothing is marching-cubes
// output, whose every vertex lies on an edge of the volume's grid. Such a vertex has two of its
// three coordinates exactly on grid planes (the edge's line) and the third between two planes.
// Where most vertices carry that signature on axis-aligned planes that are evenly spaced, the
// mesh tells its grid as a volume would (Mesh::voxel_axes): thin plates, narrow gaps and
// staircase faces below that grid are then "below resolution" exactly as for the volume.
//
// Not detected (and said so by nullopt): smoothed or decimated exports (the vertices left the
// grid's edges), meshes rotated after extraction, regular meshes that are not marching-cubes
// output (every coordinate of a structured grid's vertex lies on a plane: three, not two).
#pragma once

#include "mesh/field_of_view.h"
#include "mesh/mesh.h"

#include <optional>

namespace glint {

struct DetectedGrid {
    Eigen::Vector3d spacing = Eigen::Vector3d::Zero();  ///< mesh units, along x, y, z
    double on_edges = 0.0;  ///< share of vertices with exactly two coordinates on grid planes
};

/// The grid `mesh` was extracted on, or nullopt. Needs at least 200 vertices.
[[nodiscard]] std::optional<DetectedGrid> detect_voxel_grid(const Mesh& mesh);

/// Where a mesh on grid `g` was cut by its volume's edge: a face of its bounding box that holds
/// at least 10 of its open-border vertices (within a hundredth of a voxel) is the volume's
/// edge, as marching cubes leaves it; the box reaches without limit where no face is cut. Empty
/// when no face is: a closed surface, or borders of its own (a segmentation's edge, a
/// resection) say nothing of where the scan saw. What a volume's surface carries as its field
/// of view (mesh/field_of_view.h), read back from a mesh file.
[[nodiscard]] FieldOfView field_of_view_of_cut(const Mesh& mesh, const DetectedGrid& g);

}  // namespace glint
