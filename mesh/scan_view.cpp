#include "mesh/scan_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace glint {

namespace {

// note: 4096 area-weighted normals put the 99th percentile within a fraction of a degree of the
// whole surface's (the bunny scans: ≤ 0.3°) at a few ms for 1024 directions.
constexpr std::size_t kSamples = 4096;
constexpr std::size_t kCoarseDirections = 1024;
constexpr double kQuantile = 0.01;  // of the cosines: the 99th percentile angle

// Unit normals of triangles taken at equal steps of cumulative area: an area-weighted sample.
std::vector<Vec3d> sampled_normals(const Mesh& mesh) {
    std::vector<Vec3d> normal;
    std::vector<double> cumulative;
    double total = 0.0;
    for (const auto& t : mesh.triangles) {
        const Vec3d a = mesh.positions[t[0]].cast<double>();
        const Vec3d c = (mesh.positions[t[1]].cast<double>() - a)
                            .cross(mesh.positions[t[2]].cast<double>() - a);
        const double twice_area = c.norm();
        if (!(twice_area > 0.0) || !std::isfinite(twice_area)) continue;
        total += twice_area;
        normal.push_back(c / twice_area);
        cumulative.push_back(total);
    }
    std::vector<Vec3d> sample;
    if (normal.empty()) return sample;
    const std::size_t m = std::min(kSamples, normal.size());
    sample.reserve(m);
    std::size_t i = 0;
    for (std::size_t k = 0; k < m; ++k) {
        const double at = (static_cast<double>(k) + 0.5) * total / static_cast<double>(m);
        while (i + 1 < cumulative.size() && cumulative[i] < at) ++i;
        sample.push_back(normal[i]);
    }
    return sample;
}

// The cosine at the kQuantile of the normals' cosines to d: the 99th percentile angle's.
double low_cosine(const std::vector<Vec3d>& normals, const Vec3d& d, std::vector<double>& work) {
    work.resize(normals.size());
    for (std::size_t i = 0; i < normals.size(); ++i) work[i] = normals[i].dot(d);
    const auto k = static_cast<std::ptrdiff_t>(kQuantile * static_cast<double>(work.size()));
    std::nth_element(work.begin(), work.begin() + k, work.end());
    return work[static_cast<std::size_t>(k)];
}

Vec3d fibonacci_direction(std::size_t i, std::size_t count) {
    const double z = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(count);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = std::numbers::pi * (3.0 - std::sqrt(5.0)) * static_cast<double>(i);
    return {r * std::cos(phi), r * std::sin(phi), z};
}

}  // namespace

std::optional<ScanView> one_view_scan(const Mesh& mesh) {
    const std::vector<Vec3d> normals = sampled_normals(mesh);
    if (normals.empty()) return std::nullopt;
    std::vector<double> work;
    Vec3d best{0, 0, 1};
    double best_cos = -2.0;
    for (std::size_t i = 0; i < kCoarseDirections; ++i) {
        const Vec3d d = fibonacci_direction(i, kCoarseDirections);
        const double c = low_cosine(normals, d, work);
        if (c > best_cos) {
            best_cos = c;
            best = d;
        }
    }
    // The coarse directions lie ~6° apart: a pattern search round the best halves its step
    // down to a few hundredths of a degree.
    for (double step = 4.0 * std::numbers::pi / 180.0; step > 5e-4; step *= 0.5) {
        const Vec3d u = best.unitOrthogonal();
        const Vec3d v = best.cross(u);
        bool moved = true;
        while (moved) {
            moved = false;
            for (int k = 0; k < 8; ++k) {
                const double a = k * std::numbers::pi / 4.0;
                const Vec3d d = (best + step * (std::cos(a) * u + std::sin(a) * v)).normalized();
                const double c = low_cosine(normals, d, work);
                if (c > best_cos + 1e-12) {
                    best_cos = c;
                    best = d;
                    moved = true;
                }
            }
        }
    }
    const double cone = std::acos(std::clamp(best_cos, -1.0, 1.0)) * 180.0 / std::numbers::pi;
    if (cone > kMaxScanConeDeg) return std::nullopt;
    return ScanView{.direction = best, .cone_deg = cone};
}

}  // namespace glint
