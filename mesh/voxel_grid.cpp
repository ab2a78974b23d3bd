#include "mesh/voxel_grid.h"

#include "mesh/components.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace glint {

namespace {

// A coordinate value shared by this many vertices lies on a grid plane: a marching-cubes
// surface crosses each plane along a curve of many edge vertices, while an interpolated
// coordinate repeats only by chance.
constexpr std::uint32_t kPlaneCount = 3;
// The marching-cubes signature must hold for most vertices (the rest: coordinates that fall on
// a plane by chance, iso values met exactly at a voxel).
constexpr double kMinOnEdges = 0.6;
// Repeated values must lie on one lattice of planes within this share of its spacing …
constexpr double kSpacingTolerance = 0.02;
constexpr double kMinMultiples = 0.9;  // … for this share of the vertices on them
constexpr std::size_t kMinPlanes = 5;
constexpr std::size_t kMinVertices = 200;

using Counts = std::unordered_map<std::uint32_t, std::uint32_t>;

// note: exact float bits, with -0 read as +0: marching cubes writes each plane's coordinate
// from one expression, so equal planes give equal bits.
std::uint32_t bits(float x) { return std::bit_cast<std::uint32_t>(x == 0.0f ? 0.0f : x); }

// The spacing of the planes of one axis (0: none evenly spaced). A grid plane carries the
// many vertices of the surface's crossing with it; a value that repeats by chance (integer CT
// values make interpolated coordinates repeat) carries a few. The spacing is read from the
// strong planes (at least a tenth of the 90th percentile's count) and must place nearly all
// vertices on repeated values (kMinMultiples of them, by count) on one lattice.
double plane_spacing(const Counts& counts) {
    std::vector<std::pair<double, std::uint32_t>> planes;
    for (const auto& [b, n] : counts)
        if (n >= kPlaneCount) planes.emplace_back(static_cast<double>(std::bit_cast<float>(b)), n);
    if (planes.size() < kMinPlanes) return 0.0;
    std::vector<std::uint32_t> n_sorted;
    for (const auto& p : planes) n_sorted.push_back(p.second);
    const auto p90 = n_sorted.begin() + static_cast<std::ptrdiff_t>(9 * n_sorted.size() / 10);
    std::nth_element(n_sorted.begin(), p90, n_sorted.end());
    const double strong = std::max(static_cast<double>(kPlaneCount), 0.1 * *p90);
    std::vector<double> at;
    for (const auto& p : planes)
        if (p.second >= strong) at.push_back(p.first);
    if (at.size() < kMinPlanes) return 0.0;
    std::sort(at.begin(), at.end());
    std::vector<double> gaps;
    for (std::size_t i = 1; i < at.size(); ++i) gaps.push_back(at[i] - at[i - 1]);
    const auto mid = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2);
    std::nth_element(gaps.begin(), mid, gaps.end());
    const double s = *mid;
    if (!(s > 0.0) || !std::isfinite(s)) return 0.0;
    double on = 0.0, all = 0.0;
    for (const auto& p : planes) {
        const double q = (p.first - at.front()) / s;
        all += p.second;
        if (std::abs(q - std::round(q)) <= kSpacingTolerance) on += p.second;
    }
    return on >= kMinMultiples * all ? s : 0.0;
}

}  // namespace

std::optional<DetectedGrid> detect_voxel_grid(const Mesh& mesh) {
    const std::size_t n = mesh.positions.size();
    if (n < kMinVertices) return std::nullopt;
    Counts counts[3];
    for (auto& c : counts) c.reserve(n / 4);
    for (const auto& p : mesh.positions)
        for (int k = 0; k < 3; ++k) ++counts[k][bits(p[k])];
    std::size_t on_edges = 0;
    for (const auto& p : mesh.positions) {
        int on = 0;
        for (int k = 0; k < 3; ++k) on += counts[k][bits(p[k])] >= kPlaneCount ? 1 : 0;
        on_edges += on == 2 ? 1 : 0;
    }
    DetectedGrid g;
    g.on_edges = static_cast<double>(on_edges) / static_cast<double>(n);
    if (g.on_edges < kMinOnEdges) return std::nullopt;
    for (int k = 0; k < 3; ++k) {
        g.spacing[k] = plane_spacing(counts[k]);
        if (!(g.spacing[k] > 0.0)) return std::nullopt;
    }
    return g;
}

FieldOfView field_of_view_of_cut(const Mesh& mesh, const DetectedGrid& g) {
    // note: a box without a cut face reaches 1e6 sizes beyond the mesh: without limit for
    // every surface it is compared with, yet finite for the depth arithmetic.
    constexpr std::size_t kMinCutVertices = 10;
    constexpr double kUnbounded = 1e6;
    FieldOfView fov;
    if (mesh.positions.empty()) return fov;
    const auto border = border_vertices(mesh);
    const Bounds box = bounds(mesh);
    const double far =
        kUnbounded * std::max(static_cast<double>(box.diagonal()), g.spacing.maxCoeff());
    std::size_t cut_at[3][2] = {{0, 0}, {0, 0}, {0, 0}};
    for (std::size_t v = 0; v < border.size(); ++v) {
        if (!border[v]) continue;
        for (int k = 0; k < 3; ++k) {
            const double x = mesh.positions[v][k], tol = 0.01 * g.spacing[k];
            const double lo = box.min[k], hi = box.max[k];
            if (std::abs(x - lo) <= tol) ++cut_at[k][0];
            if (std::abs(x - hi) <= tol) ++cut_at[k][1];
        }
    }
    ViewBox b;
    bool any = false;
    for (int k = 0; k < 3; ++k) {
        const bool lo = cut_at[k][0] >= kMinCutVertices, hi = cut_at[k][1] >= kMinCutVertices;
        any = any || lo || hi;
        const double from = lo ? box.min[k] : box.min[k] - far;
        const double to = hi ? box.max[k] : box.max[k] + far;
        b.origin[k] = from;
        b.extent[k] = to - from;
    }
    if (any) fov.boxes.push_back(b);
    return fov;
}

}  // namespace glint
