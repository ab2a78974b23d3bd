// Ground truth and scores for pairs derived from real surfaces (issue: detection that holds on
// re-tessellated real scans).
//
// Truth, exact for the meshes written: a reference vertex is damaged iff it lies in a damage's
// footprint and its exact point-to-surface distance to the damaged examined surface (placed
// back with the true motion, before noise) exceeds kDamageLabelThreshold (10 %) of that
// damage's depth. The same rule for every kind of damage, whatever the tessellations.
#pragma once

#include "decision/regions.h"
#include "mesh/damage.h"
#include "mesh/mesh.h"
#include "volume/edit.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace glint {

struct PairTruth {
    std::vector<std::uint8_t> damaged;    ///< per reference vertex: 1 = damaged
    std::vector<std::int32_t> damage_id;  ///< per reference vertex: 1-based damage, 0 = none
};

/// `damaged_examined`: the examined surface after its damages, before noise and motion, in the
/// reference's frame. `footprint`: per reference vertex, the damage whose footprint holds it
/// (mesh/damage.h labels of the same damages applied to a copy of the reference).
[[nodiscard]] PairTruth distance_truth(const Mesh& reference, const Mesh& damaged_examined,
                                       const std::vector<std::int32_t>& footprint,
                                       const std::vector<DamageSpec>& damages);

/// note: a quarter of the coarser scan's largest voxel edge. Two noiseless scans of one
/// surface on different grids place it apart by partial volume, a tenth of a voxel or two; a
/// quarter is beyond that and well under any erosion a scan can show (CBCT 0.4 mm: 0.1 mm of a
/// 0.5 mm cap; CThead's 2 mm slices: 0.5 mm of a 3 mm ball).
inline constexpr double kErosionLabelVoxels = 0.25;

/// Truth of a CT pair made in the volume (issue 50, item 6), from its noiseless scans: a
/// reference vertex is damaged where it lies within `reach` of an erosion's ball (the scene's
/// balls, reference frame) and the noiseless examined surface (placed back in the reference's
/// frame) lies at least `depth` farther from it than the noiseless reference surface does.
/// Partial volume, blur, a ball that cuts through thin bone (the surface gone: far from any
/// examined surface) and an erosion value above the iso value (nothing removed) are what the
/// scans show, not what the balls say. damage_id: the nearest ball's, 1-based.
[[nodiscard]] PairTruth erosion_truth(const Mesh& reference, const Mesh& noiseless_reference,
                                      const Mesh& noiseless_examined,
                                      std::span<const Erosion> erosions, double reach,
                                      double depth);

/// Unsigned distance of every reference vertex to a surface in the reference's frame.
[[nodiscard]] std::vector<float> vertex_distances(const Mesh& reference, const Mesh& surface);

/// How the regions of a decision (or of a baseline mask) meet the truth, region by region.
struct RegionTally {
    std::size_t regions = 0;
    std::size_t false_regions = 0;     ///< regions holding no damaged vertex
    std::size_t damages = 0;           ///< damages with at least one damaged vertex
    std::size_t damages_detected = 0;  ///< of those, touched by a region
    /// Region vertices whose true distance is below `min_true_distance` (pairs without labels).
    std::size_t close_region_vertices = 0;
};

/// `region_of_vertex[v]`: region id (0 = none). `truth` may be empty (then only
/// close_region_vertices is meaningful); `true_distance` may be empty.
[[nodiscard]] RegionTally tally_regions(const std::vector<std::int32_t>& region_of_vertex,
                                        const PairTruth* truth,
                                        const std::vector<float>& true_distance,
                                        double min_true_distance);

/// What a user of a plain distance threshold gets (CloudCompare's C2M / Open3D's distance
/// thresholded at 10 % of the depth): |distance| > threshold, connected components of the
/// reference as regions.
struct BaselineResult {
    double threshold = 0.0;
    std::vector<std::int32_t> region_of_vertex;
    std::size_t regions = 0;
};
[[nodiscard]] BaselineResult distance_baseline(const Mesh& reference,
                                               const std::vector<float>& distance,
                                               double threshold);

}  // namespace glint
