#include "mesh/field_of_view.h"

#include <algorithm>
#include <limits>

namespace glint {

double ViewBox::depth_inside(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - origin;
    double depth = std::numeric_limits<double>::infinity();
    for (Eigen::Index a = 0; a < 3; ++a) {
        const double length = axes.col(a).norm();
        if (!(length > 0)) continue;
        const double q = axes.col(a).dot(d) / (length * length);  // index along axis a
        depth = std::min({depth, q * length, (extent[a] - q) * length});
    }
    return depth;
}

double FieldOfView::depth_inside(const Eigen::Vector3d& p) const {
    double depth = std::numeric_limits<double>::infinity();
    for (const auto& b : boxes) depth = std::min(depth, b.depth_inside(p));
    for (const auto& b : balls) depth = std::min(depth, b.radius - (p - b.center).norm());
    return depth;
}

void FieldOfView::transform(const Eigen::Isometry3d& new_from_old) {
    for (auto& b : boxes) {
        b.origin = new_from_old * b.origin;
        b.axes = new_from_old.linear() * b.axes;
    }
    for (auto& b : balls) b.center = new_from_old * b.center;
}

void FieldOfView::scale(double factor) {
    for (auto& b : boxes) {
        b.origin *= factor;
        b.axes *= factor;
    }
    for (auto& b : balls) {
        b.center *= factor;
        b.radius *= factor;
    }
}

}  // namespace glint
