// Which way a region is looked at (issue 51): the direction and the sweep view that see the most
// of it face on and unoccluded, not the one of its strongest pixel or its mean normal when
// another sheet of the surface stands in front.
#include "analysis/region_views.h"

#include "mesh/normals.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

// A square plate of n × n cells at height z, facing +z (or −z), appended to `m`.
void add_plate(Mesh& m, double half, double z, int n, bool up) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.positions.emplace_back(static_cast<float>(-half + 2 * half * i / n),
                                     static_cast<float>(-half + 2 * half * j / n),
                                     static_cast<float>(z));
    const auto at = [&](int i, int j) {
        return base + static_cast<std::uint32_t>(j * (n + 1) + i);
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            if (up) {
                m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            } else {
                m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
                m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            }
        }
}

// Region 1: the vertices of the first plate within `radius` of its centre.
std::vector<std::int32_t> central_region(const Mesh& m, std::size_t first_plate, double radius) {
    std::vector<std::int32_t> ids(m.vertex_count(), 0);
    for (std::size_t v = 0; v < first_plate; ++v)
        if (m.positions[v].head<2>().norm() <= radius) ids[v] = 1;
    return ids;
}

TEST(ChooseRegionViews, SeesAnOpenRegionSquareOn) {
    Mesh m;
    add_plate(m, 30, 0, 30, true);
    compute_vertex_normals(m);
    const auto ids = central_region(m, m.vertex_count(), 5);
    std::vector<Region> regions{Region{.id = 1}};
    choose_region_views(m, nullptr, SweepPlan{}, 0, ids, regions);
    EXPECT_GT(regions[0].view_direction.z(), 0.999) << regions[0].view_direction.transpose();
    EXPECT_NEAR(regions[0].visible_fraction, 1.0, 1e-6);
}

// A roof over the region (a plate 20 mm across, 2 mm above it, facing away): square on, the
// region is hidden; only a grazing direction past the roof's edge sees it.
TEST(ChooseRegionViews, LooksPastASheetThatHidesTheRegionSquareOn) {
    Mesh m;
    add_plate(m, 30, 0, 30, true);
    const std::size_t floor = m.vertex_count();
    add_plate(m, 10, 2, 10, true);  // its top faces up, its underside hides the region
    compute_vertex_normals(m);
    const auto ids = central_region(m, floor, 3);
    std::vector<Region> regions{Region{.id = 1}};
    choose_region_views(m, nullptr, SweepPlan{}, 0, ids, regions);
    const Vec3d d = regions[0].view_direction;
    std::printf("roofed region: direction (%.3f, %.3f, %.3f), visible %.3f\n", d.x(), d.y(), d.z(),
                regions[0].visible_fraction);
    EXPECT_GT(regions[0].visible_fraction, 0.02);
    EXPECT_LT(d.z(), 0.4) << "the mean normal is hidden by the roof";
    EXPECT_GT(d.z(), 0.0);
}

// The sweep view kept is the one facing the region, inside its frame, not one grazing it.
TEST(ChooseRegionViews, PicksTheSweepViewFacingTheRegion) {
    const Mesh sphere = make_phantom({.kind = PhantomKind::Sphere, .resolution = 4});
    std::vector<std::int32_t> ids(sphere.vertex_count(), 0);
    const Vec3d pole = Vec3d(1, 1, 0.5).normalized();
    for (std::size_t v = 0; v < ids.size(); ++v)
        if (sphere.positions[v].cast<double>().normalized().dot(pole) > 0.97) ids[v] = 1;
    const SweepPlan plan = make_sweep_plan(sphere, {});
    std::vector<Region> regions{Region{.id = 1, .best_view = 0}};
    choose_region_views(sphere, nullptr, plan, 0, ids, regions);
    ASSERT_GE(regions[0].best_view, 0);
    const View& v = plan.views[static_cast<std::size_t>(regions[0].best_view)].view;
    const Vec3d looking = direction_from_az_el(v.azimuth_deg, v.elevation_deg);
    std::printf("region towards (1, 1, 0.5): view az %.0f el %.0f, %.1f deg off\n", v.azimuth_deg,
                v.elevation_deg, std::acos(looking.dot(pole)) * 180.0 / std::numbers::pi);
    // The rotary plan's views lie 30° apart: the nearest is within about 20° of the region.
    EXPECT_GT(looking.dot(pole), std::cos(20.0 * std::numbers::pi / 180.0));
    EXPECT_GT(regions[0].view_direction.dot(pole), 0.97);
}

}  // namespace
}  // namespace glint
