#include "volume/phantom.h"

#include <algorithm>
#include <cmath>

namespace glint {

double ellipsoid_signed_distance(const Vec3d& p, const Vec3d& center, const Vec3d& radii) {
    const Vec3d q = (p - center).cwiseQuotient(radii);
    const double len = q.norm();
    if (len == 0) return -radii.minCoeff();
    // ∇F = q / (|q| r) componentwise.
    const Vec3d grad = q.cwiseQuotient(radii) / len;
    return (len - 1.0) / grad.norm();
}

Volume make_ellipsoid_volume(const EllipsoidVolumeOptions& o) {
    Volume v;
    v.geometry = o.grid;
    const VolumeGeometry& g = v.geometry;
    v.voxels.resize(g.voxel_count());
    const Eigen::Matrix3d axes = g.direction * g.spacing.asDiagonal();
    for (std::size_t k = 0; k < g.size[2]; ++k)
        for (std::size_t j = 0; j < g.size[1]; ++j)
            for (std::size_t i = 0; i < g.size[0]; ++i) {
                const Vec3d p = g.physical_from_index(Vec3d(double(i), double(j), double(k)));
                const double d = ellipsoid_signed_distance(p, o.center, o.radii);
                // The normal direction, for the voxel's extent along it: Σ |axis · n|.
                const Vec3d q = (p - o.center).cwiseQuotient(o.radii);
                const Vec3d n =
                    q.norm() > 0 ? Vec3d(q.cwiseQuotient(o.radii).normalized()) : Vec3d::UnitX();
                const double extent = (axes.transpose() * n).cwiseAbs().sum();
                const double inside = std::clamp(0.5 - d / (2.0 * extent), 0.0, 1.0);
                v.voxels[g.offset(i, j, k)] =
                    static_cast<float>(o.outside + (o.inside - o.outside) * inside);
            }
    return v;
}

}  // namespace glint
