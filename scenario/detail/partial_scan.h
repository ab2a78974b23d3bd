// Partial scans and fields of view made from whole surfaces (issue 24: "partial scans cut from
// the jaw", "cropped fields of view that differ"): a surface keeps only the side of a plane, as
// a scanner that saw one side of the object, or a CT whose field of view ends there. The cut
// border is jagged along the triangles, as a real scan's edge is; the ground truth stays on the
// reference (a damage beyond the examined cut is not there to be found).
//
//   [reference] or [examined]
//   keep_side = [x, y, z, nx, ny, nz]   # a point of the plane and the normal of the kept side,
//                                       # in the reference's frame (before the pose)
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "scenario/detail/toml_reader.h"
#include "scenario/scenario.h"

#include <optional>
#include <string>

namespace glint::detail {

/// keep_side of the table, when given. \throw InputError (through `r`) for a zero normal or
/// non-finite numbers.
[[nodiscard]] std::optional<ScanCut> read_scan_cut(TableReader& r);

/// Keeps the triangles whose three corners lie on the kept side and the vertices they use.
/// Returns a note for `role`: the plane and the share of the area kept. \throw InputError when
/// nothing or everything would be kept (the plane misses the surface).
[[nodiscard]] std::string cut_scan(Mesh& mesh, const ScanCut& cut, const std::string& role);

/// crop_ball of the table, when given. \throw InputError (through `r`) for a radius ≤ 0.
[[nodiscard]] std::optional<Eigen::Vector4d> read_crop_ball(TableReader& r);

/// The reference keeps its vertices inside the ball (and the triangles among them); the
/// per-reference-vertex truth follows. Returns a note. \throw InputError when the ball holds no
/// triangle or every one.
[[nodiscard]] std::string crop_reference(ScenarioMeshes& out, const Eigen::Vector4d& ball);

/// A volume pair's cuts: the reference's as given, the examined's (given in the reference's
/// frame) moved with the examined volume.
void cut_pair(const Scenario& sc, ScenarioMeshes& out, const Rigid& examined_from_reference);

}  // namespace glint::detail
