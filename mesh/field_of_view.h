// Where an acquisition saw: the boxes a surface extracted from a volume was sampled within (the
// volume's grid, and a surface ROI when one cropped it). Beyond them the scan has no data — not
// air, not a hole: a surface that ends there ends at a field-of-view cut. The comparison reads
// it (decision/comparison.h): reference surface that the examined scan's field of view does not
// hold is "not reached", never a hole or a loss, however the surface around it looks.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace glint {

/// A parallelepiped: origin + axes · q for q in [0, extent] per axis (a volume grid: the first
/// voxel's centre, its axes scaled by the spacing, the last index; a box ROI: its lower corner,
/// the unit axes, its size). Columns of `axes` are orthogonal.
struct ViewBox {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
    Eigen::Vector3d extent = Eigen::Vector3d::Zero();

    /// The signed distance from p to the nearest face (mesh units): positive inside.
    [[nodiscard]] double depth_inside(const Eigen::Vector3d& p) const;
};

/// A ball (a sphere ROI that cropped the surface).
struct ViewBall {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    double radius = 0.0;
};

/// Every box and ball the acquisition was sampled within; a point is in view inside all of them. Empty:
/// unknown (a mesh read from a file), every point in view.
struct FieldOfView {
    std::vector<ViewBox> boxes;
    std::vector<ViewBall> balls;

    [[nodiscard]] bool empty() const { return boxes.empty() && balls.empty(); }
    /// The smallest signed depth inside over the boxes and balls (+∞ when there are none).
    [[nodiscard]] double depth_inside(const Eigen::Vector3d& p) const;
    /// new_from_old applied to every box (transform_mesh); an orthogonal linear part with
    /// determinant −1 (a reflection, reflect_mesh) is applied the same way.
    void transform(const Eigen::Isometry3d& new_from_old);
    /// Every length times `factor` (a unit conversion).
    void scale(double factor);
};

}  // namespace glint
