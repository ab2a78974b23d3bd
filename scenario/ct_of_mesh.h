// A CT scan of a solid given as a closed triangle mesh (issue 50, item 6: CBCT-class pairs):
// the mesh is the object's boundary, its inside one material (bone) and its outside another
// (soft tissue). Each voxel takes the mean of the object over its own extent (partial volume,
// 2 × 2 × 2 sub-cubes, each split by the surface's signed distance), after the object moved
// and lost material in balls (erosions, made in the volume as a disease or a bur makes them);
// then the scanner blurs and adds its correlated noise (volume/acquisition.h). Two scans of one
// mesh, each with its own voxel size and noise realisation, make a longitudinal pair whose
// ground truth is exact: the same object, the known motion, the known balls.
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "volume/acquisition.h"
#include "volume/edit.h"
#include "volume/volume.h"

#include <vector>

namespace glint {

struct MeshScan {
    Vec3d voxel_size{0.4, 0.4, 0.4};  ///< mm along the scanner's x, y, z
    float background = 1040.0f;       ///< outside the object (CT soft tissue, values ≈ HU + 1000)
    float object = 1800.0f;           ///< inside the object (cortical bone as cone-beam CT sees it)
    /// Where a point of the object goes: the scanner's frame holds moved_from_original · p.
    Rigid moved_from_original = Rigid::Identity();
    /// Balls of lost material, in the object's original frame (volume/edit.h eroded_value).
    std::vector<Erosion> erosions;
    ScannerModel scanner;
    /// mm of background around the moved object's bounding box; below 0: four voxels and three
    /// σ of the blur and of the noise's correlation.
    double margin = -1.0;
};

/// The scan: an axis-aligned grid over the moved object's bounding box and the margin, voxel
/// centres on multiples of the voxel size. Material inside a closed surface is found by the
/// signed distance near the surface and by flood fill away from it (each region of voxels
/// away from the surface takes the side of one closest-point query), so cavities stay empty.
/// \throw InputError an empty mesh, a voxel size that is no size, values that are not finite
/// or equal, a grid over the voxel budget (volume/volume.h), a bad erosion or scanner model.
[[nodiscard]] Volume scan_mesh(const Mesh& object, const MeshScan& scan);

}  // namespace glint
