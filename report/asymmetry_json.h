// report.json's "asymmetry" object (glint asymmetry, glint.asymmetry()): the symmetry plane,
// the symmetry floor and the findings side by side (analysis/asymmetry.h), one writer for both.
#pragma once

#include "analysis/asymmetry.h"
#include "report/mirror_pictures.h"
#include "report/orientation.h"

#include <string>

namespace glint {

/// The plane with its evidence and verdict as JSON text: normal, point, offset, angles to the
/// axes, source, residual (mesh units, and as text with `unit`), overlap, plausible, verdict,
/// hypotheses.
[[nodiscard]] std::string symmetry_plane_json(const SymmetryPlaneResult& plane,
                                              const std::string& unit);

/// report.json's "asymmetry" as JSON text: "plane" (as symmetry_plane_json, with "frame": the
/// patient space its numbers are in, "LPS" / "RAS", and "normal_towards": its normal named as
/// the findings' sides are), "symmetry_floor",
/// "findings" (side named by `orientation`, text, kind, depth, area, volume, …), the caveat.
[[nodiscard]] std::string asymmetry_json(const SymmetryPlaneResult& plane,
                                         const AsymmetryFindings& findings,
                                         const Orientation& orientation, const std::string& unit);

/// The plane and its residual as the pictures draw them (report/mirror_pictures.h).
[[nodiscard]] MirrorPictures mirror_pictures(const SymmetryPlaneResult& plane);

/// How the finding's side was chosen, in words (analysis/asymmetry.h pair_findings): "the side
/// whose surface bends less evenly there" or "the side with less".
[[nodiscard]] std::string side_chosen_by(const AsymmetryFinding& finding);

/// A finding in one word: "less" or "more" than the mirrored other side, or "no mirrored
/// surface".
[[nodiscard]] std::string finding_kind(const AsymmetryFinding& finding);

}  // namespace glint
