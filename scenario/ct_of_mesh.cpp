#include "scenario/ct_of_mesh.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "registration/closest_point.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace glint {

namespace {

void check(const Mesh& object, const MeshScan& scan) {
    if (object.triangle_count() == 0)
        throw InputError("CT of a mesh: the object has no triangles; expected a closed surface");
    for (Eigen::Index d = 0; d < 3; ++d)
        if (!(scan.voxel_size[d] > 0) || !std::isfinite(scan.voxel_size[d]))
            throw InputError("CT of a mesh: voxel size " + std::to_string(scan.voxel_size[d]) +
                             " along axis " + std::to_string(d) + ", expected > 0 mm");
    if (!std::isfinite(scan.background) || !std::isfinite(scan.object) ||
        scan.background == scan.object)
        throw InputError("CT of a mesh: values " + std::to_string(scan.background) + " outside, " +
                         std::to_string(scan.object) +
                         " inside; expected two different finite values");
    check_erosions(scan.erosions, "CT of a mesh");
    if (!scan.moved_from_original.matrix().allFinite())
        throw InputError("CT of a mesh: the motion holds a number that is not finite");
    if (!std::isfinite(scan.margin))
        throw InputError("CT of a mesh: the margin is not a finite number of mm");
    check_scanner(scan.scanner);
}

// The grid over the moved object's box and the margin, centres on multiples of the voxel size.
VolumeGeometry scan_grid(const Mesh& moved, const MeshScan& scan) {
    const Bounds b = bounds(moved);
    const double margin = scan.margin >= 0
                              ? scan.margin
                              : 4.0 * scan.voxel_size.maxCoeff() +
                                    3.0 * (gaussian_sigma_from_fwhm(scan.scanner.psf_fwhm) +
                                           scan.scanner.noise_correlation);
    VolumeGeometry g;
    g.spacing = scan.voxel_size;
    double count = 1.0;
    for (std::size_t d = 0; d < 3; ++d) {
        const auto e = static_cast<Eigen::Index>(d);
        const double h = scan.voxel_size[e];
        g.origin[e] = std::floor((double(b.min[e]) - margin) / h) * h;
        const double n = std::ceil((double(b.max[e]) + margin - g.origin[e]) / h) + 1.0;
        count *= n;
        g.size[d] = static_cast<std::size_t>(std::min(n, 1e12));
    }
    if (count > double(kDefaultMaxVoxels))
        throw InputError("CT of a mesh: voxel size " + std::to_string(scan.voxel_size.minCoeff()) +
                         " mm gives " + std::to_string(static_cast<long long>(count)) +
                         " voxels, above the budget of " + std::to_string(kDefaultMaxVoxels));
    return g;
}

// Twice the signed volume's sign: a surface wound inside out (as some exporters write it) has
// its normals pointing in, and its signed distances are turned back.
double orientation(const Mesh& m) {
    double v = 0.0;
    for (const auto& t : m.triangles) {
        const Vec3d a = m.positions[t[0]].cast<double>(), b = m.positions[t[1]].cast<double>(),
                    c = m.positions[t[2]].cast<double>();
        v += a.dot(b.cross(c));
    }
    return v < 0 ? -1.0 : 1.0;
}

enum : std::uint8_t { kFar = 0, kNear = 1, kInside = 2, kOutside = 3 };

}  // namespace

Volume scan_mesh(const Mesh& object, const MeshScan& scan) {
    check(object, scan);
    Mesh moved = object;
    transform_mesh(moved, scan.moved_from_original);
    const ClosestPointIndex index(moved);
    const double sign = orientation(moved);
    Volume out;
    out.stored_type = "float";
    out.geometry = scan_grid(moved, scan);
    const VolumeGeometry& g = out.geometry;
    const auto& n = g.size;
    std::vector<std::uint8_t> state(g.voxel_count(), kFar);

    // Voxels within one voxel of a triangle's box: the surface may cross them.
    for (const auto& t : moved.triangles) {
        Vec3d lo = Vec3d::Constant(1e300), hi = Vec3d::Constant(-1e300);
        for (int c = 0; c < 3; ++c) {
            const Vec3d i = g.index_from_physical(moved.positions[t[c]].cast<double>());
            lo = lo.cwiseMin(i);
            hi = hi.cwiseMax(i);
        }
        std::array<std::size_t, 3> a{}, b{};
        for (std::size_t d = 0; d < 3; ++d) {
            const auto e = static_cast<Eigen::Index>(d);
            a[d] = static_cast<std::size_t>(std::max(0.0, std::floor(lo[e]) - 1.0));
            b[d] = static_cast<std::size_t>(std::min(double(n[d] - 1), std::ceil(hi[e]) + 1.0));
        }
        for (std::size_t k = a[2]; k <= b[2]; ++k)
            for (std::size_t j = a[1]; j <= b[1]; ++j)
                for (std::size_t i = a[0]; i <= b[0]; ++i) state[g.offset(i, j, k)] = kNear;
    }

    // Away from the surface: each 6-connected region of voxels takes one query's side.
    std::vector<std::size_t> queue;
    for (std::size_t start = 0; start < state.size(); ++start) {
        if (state[start] != kFar) continue;
        throw_if_cancelled();
        const std::size_t i0 = start % n[0], j0 = (start / n[0]) % n[1], k0 = start / (n[0] * n[1]);
        const Vec3d p = g.physical_from_index(Vec3d(double(i0), double(j0), double(k0)));
        const std::uint8_t side = sign * index.closest(p).signed_distance < 0 ? kInside : kOutside;
        state[start] = side;
        queue.assign(1, start);
        while (!queue.empty()) {
            const std::size_t v = queue.back();
            queue.pop_back();
            const std::size_t i = v % n[0], j = (v / n[0]) % n[1], k = v / (n[0] * n[1]);
            auto visit = [&](std::size_t w) {
                if (state[w] == kFar) {
                    state[w] = side;
                    queue.push_back(w);
                }
            };
            if (i > 0) visit(v - 1);
            if (i + 1 < n[0]) visit(v + 1);
            if (j > 0) visit(v - n[0]);
            if (j + 1 < n[1]) visit(v + n[0]);
            if (k > 0) visit(v - n[0] * n[1]);
            if (k + 1 < n[2]) visit(v + n[0] * n[1]);
        }
    }

    const float bg = scan.background, obj = scan.object;
    out.voxels.resize(state.size());
    for (std::size_t v = 0; v < state.size(); ++v) out.voxels[v] = state[v] == kInside ? obj : bg;

    // Sub-cubes of half a voxel: each split by the surface's signed distance at its centre,
    // its share of material falling linearly over its own size.
    const double sub = 0.5 * g.spacing.mean();
    std::array<Vec3d, 8> offsets;
    for (int c = 0; c < 8; ++c)
        offsets[static_cast<std::size_t>(c)] =
            Vec3d(c & 1 ? 0.25 : -0.25, c & 2 ? 0.25 : -0.25, c & 4 ? 0.25 : -0.25);
    const Rigid original_from_moved = scan.moved_from_original.inverse();
    const double reach =
        sub + g.spacing.maxCoeff();  // an erosion's ramp and a voxel's half-diagonal
    auto near_erosion = [&](const Vec3d& x) {
        const Vec3d p = original_from_moved * x;
        return std::any_of(scan.erosions.begin(), scan.erosions.end(), [&](const Erosion& e) {
            return (p - e.center).norm() < e.radius + reach;
        });
    };
    auto voxel_index = [&](std::size_t v) {
        return Vec3d(double(v % n[0]), double((v / n[0]) % n[1]), double(v / (n[0] * n[1])));
    };
    auto material = [&](double fraction, const Vec3d& x) {
        const float value = bg + static_cast<float>(fraction) * (obj - bg);
        return scan.erosions.empty()
                   ? value
                   : eroded_value(value, original_from_moved * x, scan.erosions, sub);
    };

    std::vector<std::size_t> near;
    for (std::size_t v = 0; v < state.size(); ++v)
        if (state[v] == kNear) near.push_back(v);
    constexpr std::size_t kChunk = 1 << 16;
    std::vector<Vec3d> queries;
    for (std::size_t first = 0; first < near.size(); first += kChunk) {
        throw_if_cancelled();
        const std::size_t last = std::min(near.size(), first + kChunk);
        queries.clear();
        for (std::size_t q = first; q < last; ++q)
            for (const Vec3d& o : offsets)
                queries.push_back(g.physical_from_index(voxel_index(near[q]) + o));
        const std::vector<ClosestPoint> hits = index.closest(queries, 4.0 * g.spacing.maxCoeff());
        for (std::size_t q = first; q < last; ++q) {
            const bool eroded =
                !scan.erosions.empty() && near_erosion(g.physical_from_index(voxel_index(near[q])));
            double sum = 0.0;
            for (std::size_t s = 0; s < 8; ++s) {
                const std::size_t h = (q - first) * 8 + s;
                const ClosestPoint c = hits[h].found ? hits[h] : index.closest(queries[h]);
                const double fraction = std::clamp(0.5 - sign * c.signed_distance / sub, 0.0, 1.0);
                sum += eroded ? material(fraction, queries[h]) : bg + fraction * double(obj - bg);
            }
            out.voxels[near[q]] = static_cast<float>(sum / 8.0);
        }
    }

    // Material away from the surface inside an erosion's reach.
    for (const Erosion& e : scan.erosions) {
        const Vec3d c = g.index_from_physical(scan.moved_from_original * e.center);
        const Vec3d r = Vec3d::Constant(e.radius + reach).cwiseQuotient(g.spacing);
        std::array<std::size_t, 3> a{}, b{};
        for (std::size_t d = 0; d < 3; ++d) {
            const auto x = static_cast<Eigen::Index>(d);
            a[d] = static_cast<std::size_t>(
                std::clamp(std::floor(c[x] - r[x]), 0.0, double(n[d] - 1)));
            b[d] =
                static_cast<std::size_t>(std::clamp(std::ceil(c[x] + r[x]), 0.0, double(n[d] - 1)));
        }
        for (std::size_t k = a[2]; k <= b[2]; ++k)
            for (std::size_t j = a[1]; j <= b[1]; ++j)
                for (std::size_t i = a[0]; i <= b[0]; ++i) {
                    const std::size_t v = g.offset(i, j, k);
                    if (state[v] == kNear) continue;
                    const double fraction = state[v] == kInside ? 1.0 : 0.0;
                    double sum = 0.0;
                    for (const Vec3d& o : offsets)
                        sum += material(fraction, g.physical_from_index(voxel_index(v) + o));
                    out.voxels[v] = static_cast<float>(sum / 8.0);
                }
    }
    apply_scanner(out, scan.scanner);
    return out;
}

}  // namespace glint
