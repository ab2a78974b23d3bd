// Volumes sampled from an analytic object, for tests and benchmarks: an axis-aligned
// ellipsoid (physical frame) on any grid (spacing, origin, direction).
#pragma once

#include "volume/volume.h"

namespace glint {

struct EllipsoidVolumeOptions {
    VolumeGeometry grid;     ///< the voxel grid (size, spacing, origin, direction)
    Vec3d center{0, 0, 0};   ///< physical, mm
    Vec3d radii{10, 8, 6};   ///< semi-axes along physical x, y, z, mm
    float inside = 1000.0f;  ///< value deep inside
    float outside = 0.0f;    ///< value far outside
};

/// Samples the ellipsoid with partial volume: a voxel's value blends inside and outside by a
/// linear ramp of the (first-order) signed distance d to the surface, 0.5 at d = 0, over twice
/// the voxel's extent along the surface normal (the box filter of a plane, widened by one
/// voxel of scanner blur). The iso-surface at (inside + outside) / 2 is the analytic surface.
[[nodiscard]] Volume make_ellipsoid_volume(const EllipsoidVolumeOptions& options);

/// First-order signed distance from p to the ellipsoid surface (negative inside), mm: F/|∇F|
/// with F = |((p - c) / r)| - 1; exact on a sphere, O(d²·curvature) off it.
[[nodiscard]] double ellipsoid_signed_distance(const Vec3d& p, const Vec3d& center,
                                               const Vec3d& radii);

}  // namespace glint
