#include "mesh/voxel_grid.h"

#include "mesh/components.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <span>
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

// note: a tenth of the noise-free signature's strength. Measured |mean exp(2πi x / s)| at the
// grid's spacing: CThead raw marching cubes 0.52–0.75, windowed-sinc 15 iterations 0.14–0.23,
// 30 iterations at pass band 0.05 0.09–0.13, 0.8 / 1.5 mm resamplings smoothed 0.15–0.17, a
// CBCT tooth segmentation exported smoothed (OpenFullJaw) 0.07–0.14; meshes of no grid (the
// ArtiSynth jaws, the post-resection jaw, a condyle) at most 0.07, and then with quarters out
// of phase.
constexpr double kMinPeriodicity = 0.06;
// The chance value of the largest of ~10³ Fourier components of n random phases is about
// 2.7 / √n; six times that is no chance.
constexpr double kChanceMultiple = 6.0;
constexpr double kHarmonicShare = 0.5;    // a longer period's strength against the strongest's
constexpr double kMinQuarterShare = 0.4;  // each quarter's strength against the whole's
constexpr double kMaxPhaseCycles = 0.1;   // each quarter's phase against the whole's
// The periods searched, in triangle-size voxels: from a fine axis of an anisotropic grid to
// its thickest slices (CThead's 1 × 1 × 2 mm: 0.81 and 1.6).
constexpr double kMinPeriodVoxels = 0.4, kMaxPeriodVoxels = 4.0;
// note: a grid more than this many triangle-size voxels across is not searched (the
// histogram's bins and frequencies grow with its square; CBCT at 0.3 mm is 300–800 across).
constexpr double kMaxVoxelsAcross = 2048.0;
// note: 20 000 vertices read (an even stride over the mesh): chance components 0.02, a third
// of kMinPeriodicity; 50 000 cost CThead's smoothed export 0.65 s against 0.8 s for the rest of
// reading it.
constexpr std::size_t kMaxSampled = 20000;

std::complex<double> phasor_mean(std::span<const double> x, double period) {
    std::complex<double> sum = 0.0;
    const double w = 2.0 * std::numbers::pi / period;
    for (const double v : x) sum += std::polar(1.0, w * v);
    return x.empty() ? sum : sum / static_cast<double>(x.size());
}

// The period of the grid along one axis (0: none): `x` the sampled vertices' coordinate on
// it, `others` their other two coordinates, `voxel` the triangle-size voxel.
struct AxisLattice {
    double period = 0.0;
    double strength = 0.0;
};
AxisLattice axis_lattice(std::span<const double> x, std::span<const Eigen::Vector2d> others,
                         double voxel) {
    const auto [lo_it, hi_it] = std::minmax_element(x.begin(), x.end());
    const double lo = *lo_it, extent = *hi_it - *lo_it;
    if (!(extent > kMaxPeriodVoxels * voxel) || extent > kMaxVoxelsAcross * voxel) return {};
    // A histogram of bins of an eighth of a voxel (a period of 0.4 voxel is still sampled
    // three times), its Fourier components at frequencies j / extent, half a step apart.
    const double bin = voxel / 8.0;
    const std::size_t bins = static_cast<std::size_t>(extent / bin) + 1;
    std::vector<double> hist(bins, 0.0);
    for (const double v : x)
        hist[std::min(bins - 1, static_cast<std::size_t>((v - lo) / bin))] += 1;
    const double j_lo = extent / (kMaxPeriodVoxels * voxel),
                 j_hi = extent / (kMinPeriodVoxels * voxel);
    double best_j = 0.0, best = 0.0;
    for (double j = j_lo; j <= j_hi; j += 0.5) {
        const std::complex<double> step =
            std::polar(1.0, 2.0 * std::numbers::pi * j * bin / extent);
        std::complex<double> phase = std::polar(1.0, std::numbers::pi * j * bin / extent),
                             sum = 0.0;
        for (std::size_t b = 0; b < bins; ++b) {
            if (hist[b] != 0.0) sum += hist[b] * phase;
            phase *= step;
        }
        if (std::abs(sum) > best) {
            best = std::abs(sum);
            best_j = j;
        }
    }
    if (!(best_j > 0.0)) return {};
    // Refined on the vertices themselves, within half a step either side.
    AxisLattice out;
    for (int i = -10; i <= 10; ++i) {
        const double period = extent / (best_j + 0.5 * i / 10.0);
        const double strength = std::abs(phasor_mean(x, period));
        if (strength > out.strength) out = {period, strength};
    }
    const double chance = kChanceMultiple / std::sqrt(static_cast<double>(x.size()));
    if (out.strength < std::max(kMinPeriodicity, chance)) return {};
    // The strongest component may be a harmonic (vertices close to the planes carry every
    // period s / m): the grid's is the longest period whose multiple of this one is still
    // strong (the micro-CT tooth: 0.026 strongest, 0.052 its grid). A period twice the grid's
    // cancels (alternate planes at opposite phases).
    for (int m = 4; m >= 2; --m) {
        const double period = m * out.period;
        const double strength = std::abs(phasor_mean(x, period));
        if (period <= extent / kMinPlanes && strength >= kHarmonicShare * out.strength) {
            out = {period, strength};
            break;
        }
    }
    // The same lattice throughout the mesh: in each quarter across the axis (split at the
    // other two coordinates' medians) and in each quarter along it (its own quartiles). A
    // grid's planes run through the whole volume; a surface's own regularities do not (a UV
    // sphere's rings are evenly spaced only near its equator) and a symmetric surface's
    // quarters across the axis agree by symmetry alone, its slabs along the axis do not.
    const double whole_phase = std::arg(phasor_mean(x, out.period));
    const auto quartile_cuts = [](std::vector<double> v) {
        std::array<double, 3> cut{};
        for (int q = 1; q <= 3; ++q) {
            const auto at = v.begin() + static_cast<std::ptrdiff_t>(q * v.size() / 4);
            std::nth_element(v.begin(), at, v.end());
            cut[static_cast<std::size_t>(q - 1)] = *at;
        }
        return cut;
    };
    std::vector<double> across[2];
    for (int c = 0; c < 2; ++c)
        for (const auto& o : others) across[c].push_back(o[c]);
    const double mid0 = quartile_cuts(across[0])[1], mid1 = quartile_cuts(across[1])[1];
    const std::array<double, 3> along = quartile_cuts(std::vector<double>(x.begin(), x.end()));
    const auto slab = [&](double v) {
        return static_cast<int>(std::upper_bound(along.begin(), along.end(), v) - along.begin());
    };
    for (int split = 0; split < 2; ++split)
        for (int q = 0; q < 4; ++q) {
            std::vector<double> part;
            for (std::size_t i = 0; i < x.size(); ++i) {
                const bool in = split == 0 ? (others[i][0] > mid0) == ((q & 1) != 0) &&
                                                 (others[i][1] > mid1) == ((q & 2) != 0)
                                           : slab(x[i]) == q;
                if (in) part.push_back(x[i]);
            }
            const std::complex<double> c = phasor_mean(part, out.period);
            double cycles = (std::arg(c) - whole_phase) / (2.0 * std::numbers::pi);
            cycles -= std::round(cycles);
            if (part.empty() || std::abs(c) < kMinQuarterShare * out.strength ||
                std::abs(cycles) > kMaxPhaseCycles)
                return {};
        }
    return out;
}

}  // namespace

std::optional<DetectedGrid> lattice_of_vertices(const Mesh& mesh) {
    if (mesh.positions.size() < kMinVertices) return std::nullopt;
    const auto voxel = sampling_of_triangles(mesh);
    if (!voxel || !(*voxel > 0.0) || !std::isfinite(*voxel)) return std::nullopt;
    const std::size_t stride = std::max<std::size_t>(1, mesh.positions.size() / kMaxSampled);
    std::vector<Vec3d> at;
    for (std::size_t v = 0; v < mesh.positions.size(); v += stride) {
        const Vec3d p = mesh.positions[v].cast<double>();
        if (p.allFinite()) at.push_back(p);
    }
    if (at.size() < kMinVertices) return std::nullopt;
    DetectedGrid g;
    g.smoothed = true;
    g.periodicity = 1.0;
    std::vector<double> x(at.size());
    std::vector<Eigen::Vector2d> others(at.size());
    for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        for (std::size_t i = 0; i < at.size(); ++i) {
            x[i] = at[i][k];
            others[i] = {at[i][a], at[i][b]};
        }
        const AxisLattice l = axis_lattice(x, others, *voxel);
        if (!(l.period > 0.0)) return std::nullopt;
        g.spacing[k] = l.period;
        g.periodicity = std::min(g.periodicity, l.strength);
    }
    return g;
}

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
    bool exact = g.on_edges >= kMinOnEdges;
    for (int k = 0; k < 3 && exact; ++k) {
        g.spacing[k] = plane_spacing(counts[k]);
        exact = g.spacing[k] > 0.0;
    }
    if (exact) return g;
    return lattice_of_vertices(mesh);
}

std::optional<double> sampling_of_triangles(const Mesh& mesh) {
    if (mesh.triangles.size() < kMinVertices) return std::nullopt;
    std::vector<double> area;
    area.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        const Vec3d a = mesh.positions[t[0]].cast<double>();
        const double twice = (mesh.positions[t[1]].cast<double>() - a)
                                 .cross(mesh.positions[t[2]].cast<double>() - a)
                                 .norm();
        if (twice > 0.0 && std::isfinite(twice)) area.push_back(0.5 * twice);
    }
    if (area.size() < kMinVertices) return std::nullopt;
    const auto mid = area.begin() + static_cast<std::ptrdiff_t>(area.size() / 2);
    std::nth_element(area.begin(), mid, area.end());
    return std::sqrt(*mid) / kTriangleSizePerVoxel;
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
