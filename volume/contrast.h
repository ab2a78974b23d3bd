// Where a volume places its iso-surface firmly (issue 24: two CT scans of one head, each with its
// own noise and voxel size). Marching cubes puts the surface where the values cross the iso
// value; how well that place is known depends on how steeply they leave it. Beside bone, soft
// tissue or a faint process can sit within a few noise σ of the iso value for millimetres (on
// CThead at iso 1250: tissue at 1130-1230 beside a condyle): there the other scan's noise and
// partial volume decide whether the surface closes a gap, bridges to a faint structure or runs
// millimetres away — a "bump" or "dent" that is no change of the bone.
//
// The rule, per surface vertex p with normal n (pointing to the lower values), from the point
// q where the values cross the iso value along n nearest p (within e; p itself when they do not
// cross there: smoothing moves vertices off the iso-surface):
//   firm  the values fall below iso − b within one voxel outwards (q + t·n, 0 < t ≤ e) and rise
//         above iso + b within one voxel inwards (q − t·n), where e is the voxel's extent along
//         n (Σ_i |n · a_i| over the grid's scaled axes: 1-2 mm on CThead's 1 × 1 × 2 mm grid)
//         and b = kContrastSigmas·σ, σ the volume's noise (noise_sigma)
//   faint otherwise: the surface's place rests on values within b of the threshold.
// The comparison does not compare faint surface of either scan (decision/comparison.h: below
// resolution, the scans' own contrast).
#pragma once

#include "mesh/mesh.h"
#include "volume/volume.h"

#include <cstdint>
#include <vector>

namespace glint {

/// note: 3 σ — the values of one scan lie within 3 σ of another scan's of the same object for
/// 99.7 % of the voxels; on the CThead pair (σ ≈ 30 estimated, 25 added) the false bumps sat
/// where the tissue beside the bone stayed 20-120 below the iso value (1250).
inline constexpr double kContrastSigmas = 3.0;

/// The volume's noise σ, robustly: 1.4826 · the median absolute deviation of the differences
/// between neighbouring voxels along i, over √2 (edges are a minority of the voxels). 0 for a
/// noiseless volume (a phantom).
[[nodiscard]] double noise_sigma(const Volume& volume);

/// Per vertex of a surface extracted from `volume` at `iso` (physical mm, normals set), 1
/// where it is faint (see the file comment) with the band b = `band`.
[[nodiscard]] std::vector<std::uint8_t> faint_vertices(const Volume& volume, const Mesh& surface,
                                                       double iso, double band);

}  // namespace glint
