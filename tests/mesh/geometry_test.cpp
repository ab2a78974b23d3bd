#include "mesh/geometry.h"
#include "mesh/mesh.h"

#include <gtest/gtest.h>

#include <numbers>

namespace glint {
namespace {

// Projection round trips are exact up to double rounding; 1e-9 px is far below anything
// that matters and far above the ~1e-13 we see.
constexpr double kPixelTol = 1e-9;

TEST(Camera, PixelRayAndProjectAreInverseOrthographic) {
    Camera cam;
    cam.world_from_camera = look_at({0, -10, 0}, {0, 0, 0}, {0, 0, 1});
    cam.width = 64;
    cam.height = 48;
    cam.ortho_half_height = 3.0;
    const Ray ray = cam.pixel_ray(10.5, 20.5);
    const Vec3d p = ray.origin + 7.0 * ray.direction;
    const auto uvd = cam.project(p);
    EXPECT_NEAR(uvd.x(), 10.5, kPixelTol);
    EXPECT_NEAR(uvd.y(), 20.5, kPixelTol);
    EXPECT_NEAR(uvd.z(), 7.0, kPixelTol);
    EXPECT_NEAR(cam.footprint_at(1.0), 6.0 / 48, 1e-15);
}

TEST(Camera, PixelRayAndProjectAreInversePerspective) {
    Camera cam;
    cam.projection = Projection::Perspective;
    cam.world_from_camera = look_at({3, 4, 5}, {0, 0, 0}, {0, 0, 1});
    cam.fov_y_rad = 0.7;
    const Ray ray = cam.pixel_ray(200.25, 30.75);
    const auto uvd = cam.project(ray.origin + 4.0 * ray.direction);
    EXPECT_NEAR(uvd.x(), 200.25, kPixelTol);
    EXPECT_NEAR(uvd.y(), 30.75, kPixelTol);
}

TEST(Camera, ClipMatrixMapsNearToZeroFarToOneAndYDown) {
    for (auto projection : {Projection::Orthographic, Projection::Perspective}) {
        Camera cam;
        cam.projection = projection;
        cam.near_plane = 1.0;
        cam.far_plane = 9.0;
        const Eigen::Matrix4d m = cam.clip_from_world();  // camera at origin, looking at -z
        auto ndc = [&](const Vec3d& p) {
            const Eigen::Vector4d c = m * p.homogeneous();
            return Vec3d(c.head<3>() / c.w());
        };
        EXPECT_NEAR(ndc({0, 0, -1}).z(), 0.0, 1e-12);
        EXPECT_NEAR(ndc({0, 0, -9}).z(), 1.0, 1e-12);
        EXPECT_LT(ndc({0, 0.1, -2}).y(), 0.0);  // world up is NDC up = negative y in Vulkan
    }
}

TEST(LookAt, IsAProperRotationFacingTheTarget) {
    const Rigid t = look_at({1, 2, 3}, {4, 6, 3}, {0, 0, 1});
    EXPECT_NEAR(t.linear().determinant(), 1.0, 1e-12);
    Camera cam;
    cam.world_from_camera = t;
    EXPECT_TRUE(cam.forward().isApprox(Vec3d(0.6, 0.8, 0.0), 1e-12));
}

TEST(LookAt, FallsBackWhenUpIsParallelToView) {
    const Rigid t = look_at({0, 0, 10}, {0, 0, 0}, {0, 0, 1});
    EXPECT_NEAR(t.linear().determinant(), 1.0, 1e-12);
}

TEST(DirectionFromAzEl, FollowsDocumentedAxes) {
    EXPECT_TRUE(direction_from_az_el(0, 0).isApprox(Vec3d::UnitX(), 1e-12));
    EXPECT_TRUE(direction_from_az_el(90, 0).isApprox(Vec3d::UnitY(), 1e-12));
    EXPECT_TRUE(direction_from_az_el(0, 90).isApprox(Vec3d::UnitZ(), 1e-12));
}

TEST(TransformMesh, MovesPositionsAndRotatesNormals) {
    Mesh m;
    m.positions = {{1, 0, 0}};
    m.normals = {{1, 0, 0}};
    Rigid t = Rigid::Identity();
    t.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3d::UnitZ()).toRotationMatrix();
    t.translation() = Vec3d(0, 0, 5);
    transform_mesh(m, t);
    EXPECT_TRUE(m.positions[0].isApprox(Vec3f(0, 1, 5), 1e-6f));
    EXPECT_TRUE(m.normals[0].isApprox(Vec3f(0, 1, 0), 1e-6f));
    EXPECT_NEAR(rotation_angle_deg(t), 90.0, 1e-9);
}

TEST(FieldOfView, DepthInsideTheGridAndTheRoiAndItMovesWithTheMesh) {
    // A 1 × 1 × 2 grid of 11 × 11 × 6 voxels: centres from (0, 0, 0) to (10, 10, 10).
    FieldOfView f;
    f.boxes.push_back({Vec3d::Zero(), Vec3d(1, 1, 2).asDiagonal(), Vec3d(10, 10, 5)});
    EXPECT_NEAR(f.depth_inside(Vec3d(5, 5, 5)), 5.0, 1e-12);
    EXPECT_NEAR(f.depth_inside(Vec3d(5, 5, 9)), 1.0, 1e-12);
    EXPECT_NEAR(f.depth_inside(Vec3d(-2, 5, 5)), -2.0, 1e-12);
    f.balls.push_back({Vec3d(5, 5, 5), 3.0});
    EXPECT_NEAR(f.depth_inside(Vec3d(5, 5, 7)), 1.0, 1e-12) << "the ball is the nearer cut";
    EXPECT_TRUE(FieldOfView{}.empty());
    EXPECT_GT(FieldOfView{}.depth_inside(Vec3d(1e9, 0, 0)), 1e300);
    // Turned a quarter about z and moved with its mesh; scaled from cm to mm.
    Mesh m;
    m.field_of_view = f;
    Rigid turn = Rigid::Identity();
    turn.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3d::UnitZ()).toRotationMatrix();
    turn.translation() = Vec3d(100, 0, 0);
    transform_mesh(m, turn);
    EXPECT_NEAR(m.field_of_view.depth_inside(turn * Vec3d(5, 5, 7)), 1.0, 1e-9);
    EXPECT_NEAR(m.field_of_view.depth_inside(turn * Vec3d(-2, 5, 5)), -4.0, 1e-9);  // the ball
    m.field_of_view.scale(10.0);
    EXPECT_NEAR(m.field_of_view.depth_inside(10.0 * (turn * Vec3d(5, 5, 7))), 10.0, 1e-9);
}

}  // namespace
}  // namespace glint
