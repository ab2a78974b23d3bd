// Surfaces closer than the scans resolve (issue 24).
//
// A CT surface is where the voxel values cross the iso value. Where two sheets of surface lie
// within about one voxel of each other — the two sides of a thin plate of bone, a joint space
// between condyle and fossa, a narrow gap between teeth — one voxel holds both, partial volume
// mixes them, and each scan puts its iso-surface where its own sampling and noise happen to
// fall: two acquisitions of the same head differ there by millimetres (the CThead pair at
// 1 × 1 × 2 mm against 0.8 mm: ten false regions, bumps and dents of 1–2.9 mm, every one in
// such a gap or plate). No floor and no scale can separate those from damage; the honest answer
// is that the pair cannot compare there.
//
// Per reference vertex p with normal n (reference frame, examined surface fitted):
//   the reference's clearance   the nearer of the first reference surface along +n (the gap
//                               outside) and along −n (the thickness inside);
//   the examined's clearance    along the same line, the examined surface nearest p and the
//                               next examined surface beyond it on either side;
//   the voxel's extent along n  Σ_i |n · a_i| over the grid's scaled axes a_i (Mesh::voxel_axes):
//                               the width of one voxel seen along the line (1 × 1 × 2 mm:
//                               1 mm across, 2 mm along the slices' normal, 2.3 mm diagonal).
//   the reference's thinnest   across a cone: kConeRays rays into the solid, tilted kConeTiltDeg
//                               from −n, each hit distance against the voxel's extent along
//                               its own ray. A plate is thinnest along its normal, which the
//                               straight rays read; a thin process is thin *across* its tip,
//                               whose normal runs along the process (CThead's whole surface: a
//                               2 mm process along the 2 mm slices reached 2.2 mm farther in
//                               one scan, 5–10 mm of bone behind its tip along the normal).
// The vertex is *below resolution* where the smaller clearance is under kResolutionVoxels times
// the larger of the two scans' extents along n, or the cone's thinnest is under
// kResolutionVoxels voxels along its ray. One exception: where the reference resolves (its
// clearance and its cone at least that far) but the examined surface lies more than that many
// voxels from the vertex along n, material was lost or gained — an erosion that thinned the
// bone below a voxel and left its floor faint (the CThead condyle eroded by a 5 mm ball: 42 % of
// the vertices within 6.5 mm were not compared, and the loss was missed) — and the vertex stays
// compared whatever the examined scan's thinness or contrast there: partial volume moves a
// surface by less than a voxel. The reference's own faint flag still holds. A surface from a mesh file carries no grid:
// where neither surface has one, and no --resolution was given, the rule is off.
#pragma once

#include "mesh/mesh.h"
#include "mesh/surface_index.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint {

/// note: one voxel — two sheets within one voxel's width share a voxel, and its value is a
/// partial-volume mix of both. On the CThead pair (30 mm around a condyle, both acquisitions'
/// grids) one voxel flags 10 % of the surface and ≥ 60 % of every false region's vertices, and
/// none of the erosion's (the condyle there is 7.8 mm thick, free outside); 1.5 voxels flagged
/// 17 % for little more.
inline constexpr double kResolutionVoxels = 1.0;

/// note: halfway between the normal and the tangent plane. On CThead's whole bone surface
/// (the two-acquisition pair) 45° flags 12.9 % of the surface against 6.5 % for the normal
/// alone, and brings the thin process's footprint to 12 % below resolution (the footprint rule
/// drops a group above 10 %), the erosion's to 4.9 %; 30–40° left the process a region, 60°
/// flagged 17 % and moved the floors enough to add 3 false regions. The reference's cone
/// only: the examined surface's far side is read along the normal.
inline constexpr double kConeTiltDeg = 45.0;
/// note: 8 rays, every 45° about the normal (at 50°, 6 rays gave the same regions as 8).
inline constexpr int kConeRays = 8;

struct ResolutionEvidence {
    /// 1: below resolution (per reference vertex); empty when neither surface has a grid.
    std::vector<std::uint8_t> below;
    /// The smaller of the two clearances (mesh units; +inf where nothing lies along the line).
    std::vector<float> clearance;
    /// The coarser grid's staircase step along each reference vertex's normal (mesh units; 0
    /// where the vertex has no normal; staircase_step): where a face lies nearly along thick
    /// slices its staircase steps by their thickness, and two scans on different grids (or one
    /// grid under a motion) differ by more there (decision.h DecisionEvidence).
    std::vector<float> sampling;
    double flagged_area = 0.0;  ///< area of the flagged vertices (mesh units²)
    /// Of those, the area flagged because either scan's surface is faint there (its volume
    /// within a few noise σ of the iso value beside it: volume/contrast.h, Mesh::faint).
    double faint_area = 0.0;
    std::string rule;  ///< one line: the rule and the grids it read
};

/// The grids the rule reads: each surface's own (Mesh::voxel_axes), else, for a mesh read from
/// a file, an isotropic grid of `given` mesh units (the --resolution option) when set.
struct ResolutionGrids {
    std::optional<Eigen::Matrix3d> reference;
    std::optional<Eigen::Matrix3d> examined;
    bool given = false;  ///< a grid came from the option, not from a volume
    /// A grid read from a mesh file's own vertices (mesh/voxel_grid.h: marching-cubes output).
    bool reference_detected = false;
    bool examined_detected = false;
    /// Of those, a grid read from a smoothed export's periodicity (lattice_of_vertices).
    bool reference_smoothed = false;
    bool examined_smoothed = false;
};
[[nodiscard]] ResolutionGrids resolution_grids(const Mesh& reference, const Mesh& examined,
                                               std::optional<double> given);

/// The evidence above. `reference_index` / `examined_index` index `reference` and `fitted`
/// (built here when null). \pre both meshes have vertex normals; `fitted` is in the
/// reference's frame (its grid turned with it).
[[nodiscard]] ResolutionEvidence below_resolution(
    const Mesh& reference, const Mesh& fitted, const ResolutionGrids& grids,
    std::shared_ptr<const SurfaceIndex> reference_index,
    std::shared_ptr<const SurfaceIndex> examined_index);

/// The voxel's width seen along unit direction n: Σ_i |n · a_i|.
[[nodiscard]] double voxel_extent_along(const Eigen::Matrix3d& axes, const Vec3d& n);

/// The step of a grid's staircase along unit direction n: max_i |n · a_i|, the scaled axis the
/// direction leans on most. A marching-cubes surface whose normal lies near a grid axis crosses
/// that axis's slices rarely, so its terraces step by nearly the slice thickness (CThead's
/// 1 × 1 × 2 mm: 2 mm where the face lies along the slices, under 1 mm where it lies diagonally
/// across all three axes); voxel_extent_along is largest on the diagonal instead (2.4 mm), where
/// the surface is sampled most finely. On CThead under a 3° motion the distance's robust spread
/// grows 3.4× from the smallest to the largest step, but only 1.9× across the extent.
[[nodiscard]] double staircase_step(const Eigen::Matrix3d& axes, const Vec3d& n);

}  // namespace glint
