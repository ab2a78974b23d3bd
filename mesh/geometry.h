// Vocabulary shared by render/, registration/, scanner/ and the stages above: rigid transforms, rays, cameras.
//
// Conventions
// - World units are the mesh's units.
// - A rigid transform is named by its frames and reads right to left:
//   p_reference = reference_from_examined * p_examined.
// - Camera frame: x right, y up, the camera looks along -z (OpenGL convention).
//   Pixel (u, v) has its origin at the top-left corner of the image, v grows downwards;
//   pixel centres are at integer + 0.5.
#pragma once

#include "mesh/mesh.h"

#include <Eigen/Geometry>

#include <string>

namespace glint {

/// Proper rigid motion (rotation + translation), double precision.
using Rigid = Eigen::Isometry3d;

/// Applies a rigid motion to positions and normals of a mesh (in place).
void transform_mesh(Mesh& mesh, const Rigid& new_from_old);

/// Rotation angle of a rigid motion, degrees (0…180).
[[nodiscard]] double rotation_angle_deg(const Rigid& t);

/// A ray: origin + t·direction, direction unit length.
struct Ray {
    Vec3d origin;
    Vec3d direction;
};

enum class Projection { Orthographic, Perspective };

/// A pinhole or orthographic camera looking at a mesh.
struct Camera {
    Rigid world_from_camera = Rigid::Identity();
    Projection projection = Projection::Orthographic;
    int width = 256;
    int height = 256;
    /// Orthographic: half of the visible height in world units. Unused for perspective.
    double ortho_half_height = 1.0;
    /// Perspective: vertical field of view, radians. Unused for orthographic.
    double fov_y_rad = 0.5;
    double near_plane = 0.01;  ///< distance along -z, world units
    double far_plane = 100.0;  ///< distance along -z, world units

    /// World position of the camera centre (perspective eye; for orthographic, the centre of
    /// the image plane).
    [[nodiscard]] Vec3d eye() const { return world_from_camera.translation(); }
    /// Unit viewing direction (camera -z) in world coordinates.
    [[nodiscard]] Vec3d forward() const { return -world_from_camera.linear().col(2); }
    /// World ray through image point (u, v) in pixels (pixel centres at +0.5).
    [[nodiscard]] Ray pixel_ray(double u, double v) const;
    /// Projects a world point to pixel coordinates (u, v) and its depth along the view axis.
    [[nodiscard]] Eigen::Vector3d project(const Vec3d& world) const;
    /// World units covered by one pixel at a given depth along the view axis.
    [[nodiscard]] double footprint_at(double depth) const;
    /// OpenGL/Vulkan-style 4x4 clip_from_world matrix (Vulkan: y down, depth 0..1).
    [[nodiscard]] Eigen::Matrix4d clip_from_world() const;
};

/// Camera::project for many points: the camera's inverse pose and scales computed once.
class Projector {
  public:
    explicit Projector(const Camera& camera);
    /// Pixel coordinates (u, v) of a world point and its depth along the view axis, as
    /// Camera::project.
    [[nodiscard]] Eigen::Vector3d operator()(const Vec3d& world) const;

  private:
    Rigid camera_from_world_;
    bool orthographic_;
    double half_width_;   ///< orthographic: world half width; perspective: tan(fov/2)·aspect
    double half_height_;  ///< orthographic: world half height; perspective: tan(fov/2)
    double width_;
    double height_;
};

/// Camera frame looking from `eye` at `target`, `up` roughly up (must not be parallel to the
/// viewing direction; a fallback axis is used when it is).
[[nodiscard]] Rigid look_at(const Vec3d& eye, const Vec3d& target, const Vec3d& up);

/// Unit direction from azimuth/elevation in degrees: azimuth about +z from +x towards +y,
/// elevation from the xy plane towards +z. The camera of that view sits at
/// target + distance · direction and looks back at the target.
[[nodiscard]] Vec3d direction_from_az_el(double azimuth_deg, double elevation_deg);

/// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5):
/// the point, its barycentric weights, and the feature it lies on (0 = face, 1 = edge from
/// corner `index` to corner index+1, 2 = vertex `index`).
struct TrianglePoint {
    Vec3d point;
    Vec3d barycentric;
    int feature = 0;
    int index = 0;
};
[[nodiscard]] TrianglePoint closest_point_on_triangle(const Vec3d& p, const Vec3d& a,
                                                      const Vec3d& b, const Vec3d& c);

/// Closest point on a mesh by brute force over its triangles (for a handful of queries;
/// registration/ has the BVH for many).
[[nodiscard]] Vec3d closest_point_on_mesh(const Mesh& mesh, const Vec3d& p);

}  // namespace glint
