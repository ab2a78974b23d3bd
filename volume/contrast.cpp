#include "volume/contrast.h"

#include "volume/sampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {

double noise_sigma(const Volume& volume) {
    const auto& g = volume.geometry;
    if (g.size[0] < 2) return 0.0;
    // note: every 7th row keeps this under 0.1 s at 2·10⁸ voxels; rows are the noise's samples.
    std::vector<float> d;
    const std::size_t rows = g.size[1] * g.size[2];
    d.reserve(rows / 7 * (g.size[0] - 1) + g.size[0]);
    for (std::size_t row = 0; row < rows; row += 7) {
        const float* x = volume.voxels.data() + row * g.size[0];
        for (std::size_t i = 1; i < g.size[0]; ++i) {
            const float diff = x[i] - x[i - 1];
            if (std::isfinite(diff)) d.push_back(diff);
        }
    }
    if (d.empty()) return 0.0;
    const auto median = [](std::vector<float>& v) {
        auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
        std::nth_element(v.begin(), mid, v.end());
        return static_cast<double>(*mid);
    };
    const double m = median(d);
    for (auto& x : d) x = static_cast<float>(std::abs(x - m));
    return 1.4826 * median(d) / std::sqrt(2.0);
}

namespace {

// Where the values cross the iso value along the normal nearest the vertex (t along n, within a
// voxel's extent either side; 0 when they do not cross there): smoothing and decimation move
// vertices off the iso-surface, and the band is measured from the surface the volume places.
template <class Value>
double iso_crossing(const Value& value, double iso, double extent, int steps) {
    double best = 0.0, nearest = std::numeric_limits<double>::infinity();
    const double h = extent / steps;
    for (int k = -steps; k < steps; ++k) {
        const double a = value(k * h) - iso, b = value((k + 1) * h) - iso;
        if (!(a * b <= 0) || a == b) continue;
        const double t = k * h + h * a / (a - b);
        if (std::abs(t) < nearest) {
            nearest = std::abs(t);
            best = t;
        }
    }
    return best;
}

}  // namespace

std::vector<std::uint8_t> faint_vertices(const Volume& volume, const Mesh& surface, double iso,
                                         double band) {
    const auto& g = volume.geometry;
    const Eigen::Matrix3d axes = g.direction * g.spacing.asDiagonal();
    const Eigen::Matrix3d to_index = axes.inverse();
    const Vec3d first = g.physical_from_index(Vec3d::Zero());
    std::vector<std::uint8_t> faint(surface.vertex_count(), 0);
    if (!surface.has_normals()) return faint;
    constexpr int kSteps = 4;  // samples per voxel extent, each side
    const float nan = std::numeric_limits<float>::quiet_NaN();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faint.size(), 4096), [&](const auto& r) {
        for (std::size_t v = r.begin(); v != r.end(); ++v) {
            const Vec3d p = surface.positions[v].cast<double>();
            const Vec3d n = surface.normals[v].cast<double>();
            if (!(n.squaredNorm() > 0.5)) continue;  // no direction to look along
            const double extent = (axes.transpose() * n).cwiseAbs().sum();
            const auto value = [&](double t) {
                return sample_trilinear(volume, to_index * (p + t * n - first), nan);
            };
            const double t0 = iso_crossing(value, iso, extent, kSteps);
            bool low = false, high = false;  // the values left the band outwards / inwards
            for (int k = 1; k <= kSteps && !(low && high); ++k) {
                const double t = extent * k / kSteps;
                low = low || value(t0 + t) < iso - band;
                high = high || value(t0 - t) > iso + band;
            }
            faint[v] = low && high ? 0 : 1;
        }
    });
    return faint;
}

}  // namespace glint
