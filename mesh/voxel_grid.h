// The voxel grid a mesh file was extracted on, read from its vertices alone (issue 50): a
// surface exported from a CT segmentation as STL/PLY/OBJ without smoothing is marching-cubes
// output, whose every vertex lies on an edge of the volume's grid. Such a vertex has two of its
// three coordinates exactly on grid planes (the edge's line) and the third between two planes.
// Where most vertices carry that signature on axis-aligned planes that are evenly spaced, the
// mesh tells its grid as a volume would (Mesh::voxel_axes): thin plates, narrow gaps and
// staircase faces below that grid are then "below resolution" exactly as for the volume.
//
// A smoothed export has left the grid's edges but keeps their period: its vertices still crowd
// near the grid's planes, which their coordinates' Fourier components tell (lattice_of_vertices).
//
// Not detected (and said so by nullopt): meshes rotated after extraction, remeshed or decimated
// off their vertices, regular meshes that are not marching-cubes output (every coordinate of a
// structured grid's vertex lies on a plane: three, not two).
#pragma once

#include "mesh/field_of_view.h"
#include "mesh/mesh.h"

#include <optional>

namespace glint {

struct DetectedGrid {
    Eigen::Vector3d spacing = Eigen::Vector3d::Zero();  ///< mesh units, along x, y, z
    double on_edges = 0.0;  ///< share of vertices with exactly two coordinates on grid planes
    /// Read from the vertices' periodicity, not their exact planes: a smoothed export
    /// (lattice_of_vertices). Its open borders no longer lie on the volume's edge exactly.
    bool smoothed = false;
    /// The weakest axis's periodicity |mean exp(2πi x / spacing)| (1: every vertex on a plane;
    /// 0 for the exact signature, which does not measure it).
    double periodicity = 0.0;
};

/// The grid `mesh` was extracted on, or nullopt: the exact marching-cubes signature, else the
/// periodicity a smoothed export keeps (lattice_of_vertices). Needs at least 200 vertices.
[[nodiscard]] std::optional<DetectedGrid> detect_voxel_grid(const Mesh& mesh);

/// The grid of a smoothed marching-cubes export, read from its vertices' periodicity.
/// Windowed-sinc or Laplacian smoothing moves each vertex by a fraction of a voxel, mostly along
/// the surface, so the vertices still crowd near the grid's planes: along each axis their
/// coordinates carry a Fourier component of the grid's period, and of no period in between
/// (CThead at iso 1250, smoothed 15 / 30 iterations: |mean exp(2πi x / s)| 0.23 / 0.12 at the
/// 1 mm and 2 mm spacings, against 0.013 for a mesh of no grid). Per axis: the period with the
/// largest such component between 0.4 and 4 triangle-size voxels (sampling_of_triangles), from
/// a histogram of the coordinates and refined on the vertices; it is the grid's only when the
/// component is strong (kMinPeriodicity, and six times its chance value over the vertices) and
/// the same lattice holds in each quarter of the mesh (split at the other two coordinates'
/// medians: every quarter at least 0.4 of the whole's strength, its phase within a tenth of a
/// period of the whole's). Shape alone gives components at long periods that differ in phase
/// from one part of a surface to another (the ArtiSynth jaw: 0.03–0.05, phases 0.1–0.5 apart);
/// a grid's planes run through the whole volume. All three axes must show it. Not found: a
/// mesh turned after extraction, one remeshed or decimated off its vertices, meshes of no grid.
[[nodiscard]] std::optional<DetectedGrid> lattice_of_vertices(const Mesh& mesh);

/// note: √(median triangle area) of a marching-cubes surface over its voxel (the geometric mean
/// of the spacings). Measured on CThead's bone at iso 1250: 1 × 1 × 2 mm raw 0.57; resampled to
/// 0.8 mm raw 0.59, windowed-sinc smoothed (15 iterations) 0.57; to 1.5 mm raw 0.59, smoothed
/// (20) 0.57. Smoothing moves vertices along the surface but keeps the triangles' count and
/// their area: the median edge changes more (1.02 → 0.87 voxel at 0.8 mm).
inline constexpr double kTriangleSizePerVoxel = 0.58;

/// The voxel a marching-cubes surface of this mesh's triangle size was extracted on:
/// √(median triangle area) / kTriangleSizePerVoxel, where lattice_of_vertices looks for the
/// grid's period. nullopt: fewer than 200 triangles of any area.
[[nodiscard]] std::optional<double> sampling_of_triangles(const Mesh& mesh);

/// Where a mesh on grid `g` was cut by its volume's edge: a face of its bounding box that holds
/// at least 10 of its open-border vertices (within a hundredth of a voxel) is the volume's
/// edge, as marching cubes leaves it; the box reaches without limit where no face is cut. Empty
/// when no face is: a closed surface, or borders of its own (a segmentation's edge, a
/// resection) say nothing of where the scan saw. What a volume's surface carries as its field
/// of view (mesh/field_of_view.h), read back from a mesh file.
[[nodiscard]] FieldOfView field_of_view_of_cut(const Mesh& mesh, const DetectedGrid& g);

}  // namespace glint
