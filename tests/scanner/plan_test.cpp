#include "scanner/plan.h"

#include "mesh/error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

// An octahedron of radius 10 around (1, 2, 3), with outward vertex normals.
Mesh octahedron() {
    Mesh m;
    const Vec3f c(1, 2, 3);
    const Vec3f d[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& v : d) {
        m.positions.push_back(c + 10.f * v);
        m.normals.push_back(v);
    }
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return m;
}

TEST(SweepPlan, RotaryPlanHasStepsTimesRingsTimesZooms) {
    SweepPlanOptions o;
    o.azimuth_step_deg = 45;
    o.elevations_deg = {-30, 0, 30};
    o.footprints = {0.5, 0.1};
    const SweepPlan plan = make_sweep_plan(octahedron(), o);
    EXPECT_EQ(plan.views.size(), 8u * 3u * 2u);
    EXPECT_EQ(plan.columns, 8);
    EXPECT_EQ(plan.rows, 3);
    EXPECT_NEAR(plan.radius, 10.0 * o.margin, 1e-5);
    // Image size frames the sphere at the footprint.
    EXPECT_EQ(plan.sizes[0], static_cast<int>(std::ceil(2 * plan.radius / 0.5)));
    EXPECT_EQ(plan.sizes[1], static_cast<int>(std::ceil(2 * plan.radius / 0.1)));
    // Every camera looks at the target from outside the framed sphere and keeps it in view.
    for (const auto& pv : plan.views) {
        const View& v = pv.view;
        const auto uvd = v.camera.project(plan.target);
        EXPECT_NEAR(uvd.x(), v.camera.width / 2.0, 1e-6);
        EXPECT_NEAR(uvd.y(), v.camera.height / 2.0, 1e-6);
        EXPECT_GT(uvd.z() - plan.radius, v.camera.near_plane);
        EXPECT_LT(uvd.z() + plan.radius, v.camera.far_plane);
        EXPECT_NEAR(v.camera.footprint_at(uvd.z()), v.footprint, 1e-12);
    }
}

TEST(SweepPlan, FibonacciSphereIsNearUniform) {
    SweepPlanOptions o;
    o.kind = SweepPlanOptions::Kind::Sphere;
    o.sphere_views = 200;
    const SweepPlan plan = make_sweep_plan(octahedron(), o);
    ASSERT_EQ(plan.views.size(), 200u);
    // Mean direction ~0 for a uniform covering of the sphere.
    Vec3d sum = Vec3d::Zero();
    for (const auto& v : plan.views)
        sum += direction_from_az_el(v.view.azimuth_deg, v.view.elevation_deg);
    EXPECT_LT(sum.norm() / 200.0, 0.01);
}

TEST(SweepPlan, RoiKeepsOnlyViewsThatSeeIt) {
    SweepPlanOptions o;
    o.azimuth_step_deg = 90;
    o.elevations_deg = {0};
    o.roi = parse_roi("sphere:11,2,3,1");  // only the +x vertex
    const SweepPlan plan = make_sweep_plan(octahedron(), o);
    ASSERT_EQ(plan.views.size(), 1u);
    EXPECT_DOUBLE_EQ(plan.views[0].view.azimuth_deg, 0.0);
    EXPECT_EQ(plan.roi_vertices, 1u);
}

TEST(SweepPlan, RejectsEmptyPlansAndRoisAndHugeImages) {
    SweepPlanOptions o;
    o.elevations_deg.clear();
    EXPECT_THROW((void)make_sweep_plan(octahedron(), o), InputError);
    o = {};
    o.roi = parse_roi("sphere:100,100,100,1");
    EXPECT_THROW((void)make_sweep_plan(octahedron(), o), InputError);
    o = {};
    o.footprints = {1e-4};
    try {
        (void)make_sweep_plan(octahedron(), o);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("footprint"), std::string::npos);
    }
    o = {};
    o.azimuth_step_deg = -5;
    EXPECT_THROW((void)make_sweep_plan(octahedron(), o), InputError);
}

TEST(ParseRoi, ReadsSphereAndBoxAndRejectsTypos) {
    EXPECT_EQ(parse_roi("box:0,0,0,1,2,3").shape, Roi::Shape::Box);
    EXPECT_THROW((void)parse_roi("sphere:1,2,3"), InputError);
    EXPECT_THROW((void)parse_roi("cube:1,2,3,4"), InputError);
    EXPECT_THROW((void)parse_roi("sphere:1,2,x,4"), InputError);
    EXPECT_THROW((void)parse_roi("box:0,0,0,0,2,3"), InputError);
    const Roi mask = parse_roi("mask:stable.ply:keep");
    EXPECT_EQ(mask.shape, Roi::Shape::VertexMask);
    EXPECT_EQ(mask.mask_file, "stable.ply");
    EXPECT_EQ(mask.mask_property, "keep");
    EXPECT_TRUE(mask.needs_mask());
    EXPECT_EQ(parse_roi("mask:stable.ply").mask_property, "label");
    EXPECT_EQ(to_string(parse_roi(to_string(mask))).rfind("mask:stable.ply:keep", 0), 0u);
    EXPECT_THROW((void)parse_roi("mask:"), InputError);
}

}  // namespace
}  // namespace glint
