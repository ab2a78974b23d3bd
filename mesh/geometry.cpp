#include "mesh/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace glint {

void transform_mesh(Mesh& mesh, const Rigid& new_from_old) {
    const Eigen::Matrix3d r = new_from_old.linear();
    for (auto& p : mesh.positions) p = (new_from_old * p.cast<double>()).cast<float>();
    for (auto& n : mesh.normals) n = (r * n.cast<double>()).normalized().cast<float>();
    if (mesh.voxel_axes) *mesh.voxel_axes = r * *mesh.voxel_axes;
    mesh.field_of_view.transform(new_from_old);
}

double rotation_angle_deg(const Rigid& t) {
    const Eigen::AngleAxisd aa(Eigen::Matrix3d(t.linear()));
    return std::abs(aa.angle()) * 180.0 / std::numbers::pi;
}

Ray Camera::pixel_ray(double u, double v) const {
    // Normalised device coordinates in [-1, 1], y up.
    const double x_ndc = 2.0 * u / width - 1.0;
    const double y_ndc = 1.0 - 2.0 * v / height;
    const double aspect = static_cast<double>(width) / height;
    Vec3d origin_cam;
    Vec3d dir_cam;
    if (projection == Projection::Orthographic) {
        origin_cam = {x_ndc * ortho_half_height * aspect, y_ndc * ortho_half_height, 0.0};
        dir_cam = {0.0, 0.0, -1.0};
    } else {
        const double t = std::tan(0.5 * fov_y_rad);
        origin_cam = Vec3d::Zero();
        dir_cam = Vec3d(x_ndc * t * aspect, y_ndc * t, -1.0).normalized();
    }
    return {world_from_camera * origin_cam, world_from_camera.linear() * dir_cam};
}

Eigen::Vector3d Camera::project(const Vec3d& world) const { return Projector(*this)(world); }

Projector::Projector(const Camera& c)
    : camera_from_world_(c.world_from_camera.inverse()),
      orthographic_(c.projection == Projection::Orthographic),
      width_(c.width),
      height_(c.height) {
    const double aspect = static_cast<double>(c.width) / c.height;
    half_height_ = orthographic_ ? c.ortho_half_height : std::tan(0.5 * c.fov_y_rad);
    half_width_ = half_height_ * aspect;
}

Eigen::Vector3d Projector::operator()(const Vec3d& world) const {
    const Vec3d c = camera_from_world_ * world;
    const double depth = -c.z();
    // Perspective: the image plane's half extent grows with depth.
    const double scale = orthographic_ ? 1.0 : depth;
    const double x_ndc = c.x() / (half_width_ * scale);
    const double y_ndc = c.y() / (half_height_ * scale);
    return {0.5 * (x_ndc + 1.0) * width_, 0.5 * (1.0 - y_ndc) * height_, depth};
}

double Camera::footprint_at(double depth) const {
    if (projection == Projection::Orthographic) return 2.0 * ortho_half_height / height;
    return 2.0 * depth * std::tan(0.5 * fov_y_rad) / height;
}

Eigen::Matrix4d Camera::clip_from_world() const {
    // Vulkan clip space: x right, y DOWN, z in [0, 1] (0 = near). Camera looks along -z.
    const double aspect = static_cast<double>(width) / height;
    const double n = near_plane;
    const double f = far_plane;
    Eigen::Matrix4d proj = Eigen::Matrix4d::Zero();
    if (projection == Projection::Orthographic) {
        proj(0, 0) = 1.0 / (ortho_half_height * aspect);
        proj(1, 1) = -1.0 / ortho_half_height;
        proj(2, 2) = -1.0 / (f - n);  // z_ndc = (-z_cam - n) / (f - n)
        proj(2, 3) = -n / (f - n);
        proj(3, 3) = 1.0;
    } else {
        const double t = std::tan(0.5 * fov_y_rad);
        proj(0, 0) = 1.0 / (t * aspect);
        proj(1, 1) = -1.0 / t;
        proj(2, 2) = f / (n - f);  // depth 0 at near, 1 at far
        proj(2, 3) = f * n / (n - f);
        proj(3, 2) = -1.0;
    }
    return proj * world_from_camera.inverse().matrix();
}

Rigid look_at(const Vec3d& eye, const Vec3d& target, const Vec3d& up) {
    const Vec3d forward = (target - eye).normalized();
    Vec3d up_hint = up.normalized();
    // note: 1e-6 is far below any useful angle between forward and up (0.06°); below it
    // the cross product loses its direction and another axis is used.
    if (forward.cross(up_hint).norm() < 1e-6) {
        up_hint = std::abs(forward.x()) < 0.9 ? Vec3d::UnitX() : Vec3d::UnitY();
    }
    const Vec3d right = forward.cross(up_hint).normalized();
    const Vec3d true_up = right.cross(forward);
    Rigid world_from_camera = Rigid::Identity();
    world_from_camera.linear().col(0) = right;
    world_from_camera.linear().col(1) = true_up;
    world_from_camera.linear().col(2) = -forward;
    world_from_camera.translation() = eye;
    return world_from_camera;
}

Vec3d direction_from_az_el(double azimuth_deg, double elevation_deg) {
    const double az = azimuth_deg * std::numbers::pi / 180.0;
    const double el = elevation_deg * std::numbers::pi / 180.0;
    return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

TrianglePoint closest_point_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b,
                                        const Vec3d& c) {
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return {a, {1, 0, 0}, 2, 0};
    const Vec3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return {b, {0, 1, 0}, 2, 1};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return {a + v * ab, {1 - v, v, 0}, 1, 0};
    }
    const Vec3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return {c, {0, 0, 1}, 2, 2};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return {a + w * ac, {1 - w, 0, w}, 1, 2};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {b + w * (c - b), {0, 1 - w, w}, 1, 1};
    }
    const double denom = 1.0 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    return {a + ab * v + ac * w, {1 - v - w, v, w}, 0, 0};
}

Vec3d closest_point_on_mesh(const Mesh& mesh, const Vec3d& p) {
    Vec3d best = p;
    double best_d2 = std::numeric_limits<double>::max();
    for (const auto& t : mesh.triangles) {
        const TrianglePoint q = closest_point_on_triangle(p, mesh.positions[t[0]].cast<double>(),
                                                          mesh.positions[t[1]].cast<double>(),
                                                          mesh.positions[t[2]].cast<double>());
        const double d2 = (q.point - p).squaredNorm();
        if (d2 < best_d2) {
            best_d2 = d2;
            best = q.point;
        }
    }
    return best;
}

}  // namespace glint
