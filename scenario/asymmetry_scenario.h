// Scenarios with asymmetry = true (issue 27): the one surface a scenario makes (its
// [reference], with any [[damage]], noise, pose or re-meshing of [examined] applied) compared
// with its own mirror image (report/asymmetry_run.h), and the [expect] keys that check it.
// The keys are documented in docs/inputs.md ("Scenario files"):
//
//   asymmetry = true             top level; plane = "x=0" (the syntax of glint asymmetry
//                                --plane) gives the plane by hand; [registration] fit_roi
//                                restricts the plane's fit as --fit-roi does
//   [expect] findings, min_findings, max_findings, plane = "x=0", max_plane_angle_deg,
//            max_plane_offset, no_plane = true, [[expect.finding]] kind = "less", side = "+x"
//            (optionally center = [x, y, z] with max_distance: where the finding lies)
#pragma once

#include "registration/symmetry_plane.h"

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint {

namespace detail {
class TableReader;
}

struct AsymmetrySpec {
    bool enabled = false;
    std::optional<SymmetryPlane> plane;  ///< plane = "…": checked, not fitted
};

/// A finding as report.json names it: kind "less", "more" or "no mirrored surface"; side as
/// the orientation names directions ("+x" for a mesh in no stated space, "left" in LPS/RAS),
/// in the reference's frame (a scenario's pose undone).
struct FindingKindSide {
    std::string kind;
    std::string side;
    /// Outcome: the finding's centroid; [[expect.finding]] center: where it must lie, within
    /// `max_distance` (both in the reference's frame, mesh units).
    std::optional<Vec3d> center = std::nullopt;
    std::optional<double> max_distance = std::nullopt;
};

struct AsymmetryExpect {
    std::optional<std::size_t> findings;  ///< exact number of findings
    std::optional<std::size_t> min_findings;
    std::optional<std::size_t> max_findings;
    std::vector<FindingKindSide> each;   ///< [[expect.finding]]: each matches its own finding
    std::optional<SymmetryPlane> plane;  ///< expected plane, in the reference's frame
    std::optional<double> max_plane_angle_deg;  ///< with plane: both limits are required
    std::optional<double> max_plane_offset;     ///< mesh units
    bool no_plane = false;  ///< the surface has no plausible symmetry plane (a negative case)
    [[nodiscard]] bool any() const;
};

/// What an asymmetry scenario found.
struct AsymmetryOutcome {
    bool plausible = false;
    std::string verdict;
    SymmetryPlane plane;  ///< the plane used, in the reference's frame (the pose undone)
    std::optional<double> plane_angle_deg;  ///< to [expect] plane
    std::optional<double> plane_offset;     ///< to [expect] plane, at its point (mesh units)
    std::vector<FindingKindSide> findings;
    std::vector<std::string> texts;  ///< each finding in words (report.json's "text")
};

struct Scenario;

/// Reads the top-level asymmetry and plane keys into `sc.asymmetry` once the rest of the
/// scenario (its [examined] and [expect]) is read, and checks that they fit together: one
/// surface (no [examined] mesh or phantom), asymmetry [expect] keys only with asymmetry = true.
/// \throw InputError naming the file, the key, its line and what was expected.
void read_asymmetry_scenario(detail::TableReader& top, Scenario& sc);

/// Reads the asymmetry keys of [expect] (and its [[expect.finding]] tables).
void read_asymmetry_expect(detail::TableReader& expect, AsymmetryExpect& x);

/// The asymmetry [expect] entries that do not hold, appended to `failures`.
void check_asymmetry_expect(const AsymmetryExpect& x, const AsymmetryOutcome& o,
                            std::vector<std::string>& failures);

/// The angle (degrees, either normal's sign) between two planes and the distance of
/// `found`'s plane from `expected`'s point along `expected`'s normal.
[[nodiscard]] std::pair<double, double> plane_difference(const SymmetryPlane& found,
                                                         const SymmetryPlane& expected);

}  // namespace glint
