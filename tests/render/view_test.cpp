// Framing: cameras placed around a bounding sphere at a footprint, a distance or to fit.
#include "render/view.h"

#include "mesh/error.h"
#include "tests/render/test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint::test {
namespace {

constexpr double kEps = 1e-9;  // double arithmetic on unit-sized values

TEST(MakeView, OrthographicFootprintSetsTheImageScale) {
    const FramingSphere sphere{{1, 2, 3}, 5.0};
    const View v = make_view(sphere, ViewSpec{.azimuth_deg = 30,
                                              .elevation_deg = 45,
                                              .zoom = ZoomKind::Footprint,
                                              .zoom_value = 0.02,
                                              .width = 200,
                                              .height = 100});
    EXPECT_NEAR(v.footprint, 0.02, kEps);
    EXPECT_NEAR(v.camera.footprint_at(1.0), 0.02, kEps);
    EXPECT_NEAR(v.camera.ortho_half_height, 1.0, kEps);
    // The camera looks at the centre from direction_from_az_el, outside the sphere.
    const Vec3d to_eye = (v.camera.eye() - sphere.center).normalized();
    EXPECT_NEAR(to_eye.dot(direction_from_az_el(30, 45)), 1.0, kEps);
    EXPECT_GT((v.camera.eye() - sphere.center).norm(), sphere.radius);
    const Eigen::Vector3d c = v.camera.project(sphere.center);
    EXPECT_NEAR(c.x(), 100.0, 1e-6);
    EXPECT_NEAR(c.y(), 50.0, 1e-6);
    EXPECT_LT(v.camera.near_plane, c.z() - sphere.radius);
    EXPECT_GT(v.camera.far_plane, c.z() + sphere.radius);
}

TEST(MakeView, FitFramesTheWholeSphere) {
    const FramingSphere sphere{{0, 0, 0}, 2.0};
    for (const Projection proj : {Projection::Orthographic, Projection::Perspective}) {
        const View v = make_view(sphere, ViewSpec{.azimuth_deg = 10,
                                                  .elevation_deg = -20,
                                                  .width = 64,
                                                  .height = 48,
                                                  .projection = proj});
        // Points on the sphere's outline project inside the image.
        const Camera& cam = v.camera;
        const Vec3d right = cam.world_from_camera.linear().col(0);
        const Vec3d up = cam.world_from_camera.linear().col(1);
        for (const Vec3d& d : {right, Vec3d(-right), up, Vec3d(-up)}) {
            const Eigen::Vector3d px = cam.project(sphere.center + sphere.radius * d);
            EXPECT_GE(px.x(), 0.0);
            EXPECT_LE(px.x(), 64.0);
            EXPECT_GE(px.y(), 0.0);
            EXPECT_LE(px.y(), 48.0);
        }
    }
}

TEST(MakeView, PerspectiveFootprintHoldsAtTheNearestSurface) {
    const FramingSphere sphere{{0, 0, 0}, 1.0};
    const View v = make_view(sphere, ViewSpec{.zoom = ZoomKind::Footprint,
                                              .zoom_value = 0.005,
                                              .width = 256,
                                              .height = 256,
                                              .projection = Projection::Perspective,
                                              .fov_y_rad = 0.4});
    const double distance = (v.camera.eye() - sphere.center).norm();
    EXPECT_NEAR(v.camera.footprint_at(distance - 1.0), 0.005, kEps);
    EXPECT_NEAR(v.footprint, 0.005, kEps);
    const View d = make_view(sphere, ViewSpec{.zoom = ZoomKind::Distance,
                                              .zoom_value = 7.0,
                                              .projection = Projection::Perspective});
    EXPECT_NEAR((d.camera.eye() - sphere.center).norm(), 7.0, kEps);
    const View px = make_view(sphere, ViewSpec{.zoom = ZoomKind::DistancePixels,
                                               .zoom_value = 100,
                                               .width = 200,
                                               .height = 200,
                                               .projection = Projection::Perspective});
    // 100 pixels of the fit footprint 2r/h = 0.01 → 1 unit from the nearest surface.
    EXPECT_NEAR((px.camera.eye() - sphere.center).norm(), 2.0, kEps);
}

TEST(MakeView, RejectsInvalidSpecsNamingTheField) {
    const FramingSphere sphere{{0, 0, 0}, 1.0};
    try {
        (void)make_view(sphere, ViewSpec{.width = 0});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("width = 0"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)make_view(sphere, ViewSpec{.elevation_deg = 91}), InputError);
    EXPECT_THROW((void)make_view(sphere, ViewSpec{.zoom = ZoomKind::Footprint, .zoom_value = -1}),
                 InputError);
    EXPECT_THROW((void)make_view(sphere, ViewSpec{.zoom = ZoomKind::Distance,
                                                  .zoom_value = 0.5,
                                                  .projection = Projection::Perspective}),
                 InputError);
    EXPECT_THROW(
        (void)make_view(sphere, ViewSpec{.zoom = ZoomKind::DistancePixels, .zoom_value = 10}),
        InputError);
    EXPECT_THROW((void)framing_sphere(Mesh{}), InputError);
    EXPECT_THROW((void)parse_projection("fisheye"), InputError);
}

TEST(MakeView, LooksStraightDownWithoutADegenerateUpVector) {
    const View v = make_view(FramingSphere{}, ViewSpec{.elevation_deg = 90});
    EXPECT_TRUE(v.camera.world_from_camera.linear().allFinite());
    EXPECT_NEAR(v.camera.forward().z(), -1.0, kEps);
}

}  // namespace
}  // namespace glint::test
