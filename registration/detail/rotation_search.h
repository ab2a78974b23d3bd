// Rotation search: starting poses for a coarse fit that the principal-axes hypotheses miss.
// Internal (registration/coarse.cpp).
//
// A partial scan (one range scan of an object, one side of a jaw) has principal axes of its own,
// not the whole surface's, so matching principal frames starts ICP far from its place: the
// Stanford bunny's bun270 scan converged 48° off with 28 % of its samples on the reference. When
// the best principal-axes fit lays less than kSearchBelowOverlap of the examined surface onto the
// reference, poses spread evenly over all orientations are tried: rotations about axes on a
// Fibonacci sphere by 45°, 90°, 135° and 180° (plus the identity), each with the examined
// surface's centroid at the reference's centroid or pushed out along the examined surface's mean
// normal (a partial scan lies on the side it faces), each refined by a short ICP on a few samples
// and scored by its overlap (how much of the examined surface lies on the reference).
#pragma once

#include "registration/closest_point.h"
#include "registration/coarse.h"
#include "registration/detail/icp_core.h"

#include <vector>

namespace glint::detail {

/// Below this overlap of the kept principal-axes fit, the rotation search runs. note: correct
/// fits of the bunny's range scans onto bun_zipper reach 0.996–0.999; the wrong one 0.28.
inline constexpr double kSearchBelowOverlap = 0.9;

/// Share of `samples` that lie, at pose `t`, within the overlap distance of a compatible
/// reference surface (RegistrationOptions::overlap_distance × `diagonal`), and the median
/// |point-to-plane residual| of those.
struct Overlap {
    double share = 0.0;
    double median_residual = 0.0;
};
[[nodiscard]] Overlap overlap_at(const std::vector<Sample>& samples, const Rigid& t,
                                 const ClosestPointIndex& reference, const RegistrationOptions& o,
                                 double diagonal);

/// The starting poses of the search (see file comment): `reference` and `examined` are
/// samples of the two surfaces.
[[nodiscard]] std::vector<Rigid> search_poses(const std::vector<Sample>& reference,
                                              const std::vector<Sample>& examined);

/// Runs the search from every pose and returns the best fits found, best first (at most
/// `keep`), each refined with `quick` on `quick_samples` and scored by overlap.
[[nodiscard]] std::vector<CoarseHypothesis> rotation_search(
    const ClosestPointIndex& reference, const std::vector<Sample>& reference_samples,
    const std::vector<Sample>& quick_samples, const RegistrationOptions& quick, double diagonal,
    std::size_t keep = 3);

}  // namespace glint::detail
