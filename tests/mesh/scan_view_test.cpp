// The view of a one-view scan (mesh/scan_view.h): a spherical cap turned to a known direction
// gives that direction and its half-angle; surfaces a single view cannot see (a cap past its
// equator, a closed sphere) and an empty mesh give none.
#include "mesh/scan_view.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A unit-sphere cap of polar half-angle `half_deg` around `axis`, `rings` × 4·rings quads.
Mesh cap(double half_deg, const Vec3d& axis, int rings = 60) {
    const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(Vec3d::UnitZ(), axis);
    const int sectors = 4 * rings;
    Mesh m;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j < sectors; ++j) {
            const double theta = half_deg * kDeg * i / rings;
            const double phi = 2.0 * std::numbers::pi * j / sectors;
            const Vec3d p = turn * Vec3d(std::sin(theta) * std::cos(phi),
                                         std::sin(theta) * std::sin(phi), std::cos(theta));
            m.positions.push_back(p.cast<float>());
            m.normals.push_back(p.cast<float>());
        }
    const auto at = [&](int i, int j) {
        return static_cast<std::uint32_t>(i * sectors + (j % sectors));
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < sectors; ++j) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

TEST(ScanView, ACapSeenFromOneSideGivesItsAxisAndHalfAngle) {
    const Vec3d axis = Vec3d(0.3, -0.5, 0.8).normalized();
    const auto view = one_view_scan(cap(60.0, axis));
    ASSERT_TRUE(view.has_value());
    EXPECT_LT(std::acos(std::clamp(view->direction.dot(axis), -1.0, 1.0)) / kDeg, 0.5);
    // The area beyond the 99th percentile is the cap's last 1 % of area: θ ≈ 59.7°.
    EXPECT_NEAR(view->cone_deg, 59.7, 0.6);
}

TEST(ScanView, AFlatPatchIsSeenAlongItsNormal) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    const auto view = one_view_scan(m);
    ASSERT_TRUE(view.has_value());
    EXPECT_GT(view->direction.z(), 0.9999);
    EXPECT_LT(view->cone_deg, 0.5);
}

TEST(ScanView, SurfacesNoSingleViewSeesWholeAreNoOneViewScans) {
    // Past its equator (a crown, a bone cut from a CT surface) and closed.
    EXPECT_FALSE(one_view_scan(cap(100.0, Vec3d::UnitX())).has_value());
    EXPECT_FALSE(one_view_scan(cap(180.0, Vec3d::UnitY())).has_value());
    EXPECT_FALSE(one_view_scan(Mesh{}).has_value());
    // A cap just inside kMaxScanConeDeg still is one.
    EXPECT_TRUE(one_view_scan(cap(kMaxScanConeDeg - 2.0, Vec3d::UnitZ())).has_value());
}

}  // namespace
}  // namespace glint
