// The direction a one-view scan was taken from (issue 24: scanner dropouts).
//
// A range image, a one-sided laser or structured-light scan holds only surface its sensor saw
// from one direction: every normal of it faces that direction, within the incidence the
// sensor still samples. Such a surface's normals fit a cone narrower than a half-space; a
// closed surface, a CT iso-surface or a crown cut from one (a cap that turns past its
// equator) does not. The direction is the cone's axis: the one whose 99th percentile angle
// to the normals (area-weighted) is smallest; the mean normal leans towards the larger
// slopes.
//
// note (measured): the ten Stanford bunny range scans fit cones of 77–78° whose axes lie
// 3–8° from each scanner's own z (the mean normal 7–22°); the EDJ crowns of tooth_02 need
// 99–106°, the CBCT molar 140°, the jaw 148°.
#pragma once

#include "mesh/mesh.h"

#include <optional>

namespace glint {

/// A surface wider than this cone (99th percentile angle of its normals to the axis) is no
/// one-view scan. note: 85° — a sensor samples nothing at 90° incidence; the crowns, the
/// narrowest surfaces that are not one-view scans, need 99° or more.
inline constexpr double kMaxScanConeDeg = 85.0;

struct ScanView {
    Vec3d direction{0, 0, 1};  ///< unit, from the surface towards the sensor
    double cone_deg = 0.0;     ///< 99th percentile angle of the normals to it (area-weighted)
};

/// The view of a one-view scan, or nothing where the surface's normals need a wider cone than
/// kMaxScanConeDeg (or it has no area).
[[nodiscard]] std::optional<ScanView> one_view_scan(const Mesh& mesh);

}  // namespace glint
