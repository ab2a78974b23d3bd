#include "report/detail/measured_pixels.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint::detail {

bool beyond_floor(float depth, float value, const MeasuredFloor& floor) {
    if (floor.depth > 0) return std::isfinite(depth) && std::abs(depth) > floor.depth;
    return std::isfinite(value) && value > floor.normal;
}

double view_depth_floor(const ViewMeasurement& m, double least, double k) {
    std::vector<float> magnitude;
    for (std::size_t c = 0; c < m.status.size(); ++c)
        if (m.status_at(c) == MeasuredStatus::Compared && std::isfinite(m.depth_at(c)))
            magnitude.push_back(std::abs(m.depth_at(c)));
    if (magnitude.empty()) return least;
    const auto median_of = [](std::vector<float>& v) {
        const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
        std::nth_element(v.begin(), mid, v.end());
        return static_cast<double>(*mid);
    };
    const double median = median_of(magnitude);
    for (float& x : magnitude) x = static_cast<float>(std::abs(x - median));
    const double mad = median_of(magnitude);
    // 1.4826: the MAD of a normal distribution times this is its standard deviation.
    return std::max(least, median + k * 1.4826 * mad);
}

MeasuredPixels measured_pixels(const ViewMeasurement& m, const View& measured_view,
                               const View& shown, const MeasuredFloor& floor) {
    const auto w = static_cast<std::size_t>(shown.camera.width);
    const std::size_t n = w * static_cast<std::size_t>(shown.camera.height);
    MeasuredPixels out{std::vector<float>(n, std::numeric_limits<float>::quiet_NaN()),
                       std::vector<std::uint8_t>(n, 0), std::vector<std::uint8_t>(n, 0)};
    const Projector project(measured_view.camera);
    // note: any point of a pixel's ray projects to one sweep pixel (the two cameras share the
    // eye and the axis: a resize and a roll), so a point at unit distance along it serves.
    for (std::size_t p = 0; p < n; ++p) {
        const Ray ray = shown.camera.pixel_ray(static_cast<double>(p % w) + 0.5,
                                               static_cast<double>(p / w) + 0.5);
        const Eigen::Vector3d uv = project(ray.origin + ray.direction);
        const double cx = std::floor(uv.x() / m.block), cy = std::floor(uv.y() / m.block);
        if (!(cx >= 0 && cy >= 0 && cx < m.width && cy < m.height)) continue;
        const std::size_t c = static_cast<std::size_t>(cy) * static_cast<std::size_t>(m.width) +
                              static_cast<std::size_t>(cx);
        out.status[p] = m.status[c];
        if (m.status_at(c) != MeasuredStatus::Compared) continue;
        out.depth[p] = m.depth_at(c);
        out.beyond[p] = beyond_floor(out.depth[p], m.value_at(c), floor) ? 1 : 0;
    }
    return out;
}

}  // namespace glint::detail
