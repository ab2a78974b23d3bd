// The per-vertex fields of the atlas: one list of names shared by atlas.ply / .vtk / .vtp,
// report.html's field selector and glint.Analysis.fields, so every reader sees the same
// field under the same name (docs/outputs.md, "The atlas fields").
//
// Every name carries its unit: lengths in the run's unit ("_mm"; "_units" when unknown,
// mesh/units.h unit_suffix), the metric in its own ("_deg"), counts and flags in theirs.
// The decision field comes first (the active scalar of every format):
//   shape_change_<u>        signed distance to the fitted examined surface, negative = loss;
//                           measured at every vertex, seen or not; in a hole of the examined
//                           surface the depth of the surface gone (what the regions read,
//                           as atlas.png paints it), 0 where that depth is unknown
//   shape_tolerance_<u>     the tessellation tolerance at the vertex (analysis/fit.h)
// then per zoom k:
//   seen_z<k>               1 seen by a view of zoom k, 0 unseen
//   <metric>_mean_<mu>_z<k> per-vertex mean of the metric ("angle_mean_deg_z0"), 0 unseen
//   <metric>_max_<mu>_z<k>  strongest pixel of the metric at the vertex, 0 unseen
//   missing_fraction_z<k>   share of its observations with no examined surface behind, 0 unseen
//   pixels_z<k>             pixels that touched the vertex (0 unseen)
//   region_id_z<k>          the region of regions.csv the vertex belongs to, 0 none
//   not_compared_z<k>       why the vertex was not compared (decision/comparison.h): 0 compared,
//                           1 reference border, 2 examined border, 3 not reached,
//                           4 below resolution
// No field holds NaN: unseen is 0 with seen_z<k> = 0 (MeshLab aborts on a NaN quality,
// VTK's legacy reader cannot parse one).
#pragma once

#include "analysis/analysis.h"
#include "mesh/mesh.h"

#include <cstddef>
#include <string>
#include <vector>

namespace glint {

/// "shape_change_mm" (the decision field: signed shape change in the run's unit).
[[nodiscard]] std::string shape_change_field(const std::string& unit);
/// The values of that field per reference vertex: the signed distance, and in a hole of the
/// examined surface the depth of the surface gone that the regions read (zoom 0's
/// decided_shape, decision/decision.h; NaN where unknown). The distance in a hole reaches only
/// the hole's rim or the far side, so a worn cusp would read as a gain in a viewer. Empty when
/// no distance was measured.
[[nodiscard]] std::vector<float> shape_change_values(const AnalysisResult& result);
/// "shape_tolerance_mm".
[[nodiscard]] std::string shape_tolerance_field(const std::string& unit);
/// "seen_z0".
[[nodiscard]] std::string seen_field(std::size_t zoom);
/// "region_id_z0".
[[nodiscard]] std::string region_field(std::size_t zoom);
/// "pixels_z0".
[[nodiscard]] std::string pixels_field(std::size_t zoom);
/// "missing_fraction_z0".
[[nodiscard]] std::string missing_field(std::size_t zoom);
/// "not_compared_z0".
[[nodiscard]] std::string comparison_field(std::size_t zoom);
/// The metric's field: statistic "mean" or "max", e.g. "angle_mean_deg_z0".
[[nodiscard]] std::string metric_field(Metric metric, const std::string& statistic,
                                       std::size_t zoom);

/// The reference with the atlas fields in the order above, and coloured by the signed shape
/// change on the pictures' diverging map and range (report/pictures.h shape_scale), grey
/// where zoom 0 saw nothing.
[[nodiscard]] Mesh make_atlas_mesh(const Mesh& reference, const AnalysisResult& result);

}  // namespace glint
