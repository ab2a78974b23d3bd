// A region in words a clinician reads (issue 51, item 3): where it lies on the surface (its side
// and part, by the reference's anatomical axes when its space or --up states them, by mesh axes
// otherwise), which way it faces, and one plain sentence with its depth ± the uncertainty of a
// distance on this pair, its area and its volume. The method's figures (angles, floors) stay in
// report.json's other fields.
#pragma once

#include "decision/regions.h"
#include "mesh/geometry.h"
#include "report/orientation.h"

#include <string>

namespace glint {

/// A centroid this far from the surface's centre along an axis (in half-extents of the surface's
/// bounding box along it) names that side ("left", "posterior"); nearer, the axis is not named.
inline constexpr double kPlaceOffset = 0.2;

/// "right, posterior, inferior part, best seen from superior-left": the sides of the reference's
/// bounding box the region's centroid lies towards, and the direction it is best seen from
/// (Region::view_direction; left out when not chosen). "central part" when no side stands out.
[[nodiscard]] std::string region_place(const Region& region, const Bounds& reference,
                                       const Orientation& orientation);

/// "a dent 1.73 ± 0.08 mm deep over 26.9 mm² (25.1 mm³ lost), right, posterior, inferior part,
/// best seen from superior": `depth_uncertainty` is one standard deviation of a distance on this pair
/// (the shape floor's 1.4826·MAD), `unit` "" for unknown ("units"). `mirror`: the region is this
/// side against the mirrored other side (glint asymmetry): "6.55 ± 0.91 mm more than the
/// mirrored other side over 243 mm² (668 mm³ more), …".
[[nodiscard]] std::string region_sentence(const Region& region, const std::string& place,
                                          double depth_uncertainty, const std::string& unit,
                                          bool mirror = false);

/// A region's family-wise significance in words (Region::p_value): "p < 1e-6" below a
/// millionth, "p = 0.003" otherwise, "p unknown" for NaN.
[[nodiscard]] std::string significance_text(double p_value);

}  // namespace glint
