#include "volume/edit.h"

#include "mesh/cancel.h"
#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

namespace glint {

namespace {

// Trilinear interpolation at a fractional index; `outside` beyond the grid.
float sample(const Volume& v, const Vec3d& index, float outside) {
    const VolumeGeometry& g = v.geometry;
    std::array<std::size_t, 3> i0{};
    std::array<double, 3> f{};
    for (std::size_t d = 0; d < 3; ++d) {
        const double x = index[static_cast<Eigen::Index>(d)];
        if (!(x >= 0) || x > double(g.size[d] - 1)) return outside;
        i0[d] = std::min(static_cast<std::size_t>(x), g.size[d] - 2);
        f[d] = x - double(i0[d]);
    }
    double value = 0.0;
    for (int c = 0; c < 8; ++c) {
        const std::size_t di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
        const double w = (di ? f[0] : 1 - f[0]) * (dj ? f[1] : 1 - f[1]) * (dk ? f[2] : 1 - f[2]);
        if (w != 0) value += w * v.voxels[g.offset(i0[0] + di, i0[1] + dj, i0[2] + dk)];
    }
    return static_cast<float>(value);
}

std::string vec(const Vec3d& p) {
    char b[96];
    std::snprintf(b, sizeof b, "[%.9g, %.9g, %.9g]", p.x(), p.y(), p.z());
    return b;
}

}  // namespace

Rigid motion_about(const Rigid& pose, const Vec3d& pivot) {
    Rigid m = pose;
    m.translation() = pose.linear() * (-pivot) + pivot + pose.translation();
    return m;
}

namespace {

// The output grid: the input's, or the input's extent at another voxel size.
VolumeGeometry output_grid(const VolumeGeometry& in, const std::optional<Vec3d>& spacing) {
    if (!spacing) return in;
    VolumeGeometry g = in;
    for (std::size_t d = 0; d < 3; ++d) {
        const auto e = static_cast<Eigen::Index>(d);
        if (!((*spacing)[e] > 0) || !std::isfinite((*spacing)[e]))
            throw InputError("volume edit: voxel size " + std::to_string((*spacing)[e]) +
                             " along axis " + std::to_string(d) + ", expected > 0 mm");
        const double extent = double(in.size[d] - 1) * in.spacing[e];
        g.size[d] = static_cast<std::size_t>(std::floor(extent / (*spacing)[e] + 1e-9)) + 1;
        g.spacing[e] = (*spacing)[e];
    }
    if (g.voxel_count() > kDefaultMaxVoxels)
        throw InputError("volume edit: voxel size gives " + std::to_string(g.voxel_count()) +
                         " voxels, above the budget of " + std::to_string(kDefaultMaxVoxels));
    return g;
}

}  // namespace

Volume edit_volume(const Volume& in, const VolumeEdit& edit) {
    Volume out;
    out.geometry = output_grid(in.geometry, edit.spacing);
    out.stored_type = "float";
    const VolumeGeometry& g = out.geometry;
    out.voxels.resize(g.voxel_count());
    const float background = in.range()[0];
    const double ramp = in.geometry.spacing.mean();  // the erosion's partial-volume ramp
    const Rigid original_from_moved = edit.moved_from_original.inverse();
    // Sub-sample offsets (in output voxels): one at the centre, or 2 × 2 × 2 over the voxel.
    std::vector<Vec3d> offsets = {Vec3d::Zero()};
    if (edit.spacing) {
        offsets.clear();
        for (int c = 0; c < 8; ++c)
            offsets.emplace_back(c & 1 ? 0.25 : -0.25, c & 2 ? 0.25 : -0.25, c & 4 ? 0.25 : -0.25);
    }
    auto eroded = [&](const Vec3d& x) {
        const Vec3d p = original_from_moved * x;
        float value = sample(in, in.geometry.index_from_physical(p), background);
        for (const Erosion& e : edit.erosions) {
            const double d = (p - e.center).norm() - e.radius;
            const double w = std::clamp(0.5 - d / ramp, 0.0, 1.0);
            value += static_cast<float>(w) * (std::min(value, e.value) - value);
        }
        return value;
    };
    std::mt19937 random(edit.noise_seed);
    std::normal_distribution<double> noise(0.0, edit.noise_sigma > 0 ? edit.noise_sigma : 1.0);
    for (std::size_t k = 0; k < g.size[2]; ++k) {
        throw_if_cancelled();
        for (std::size_t j = 0; j < g.size[1]; ++j)
            for (std::size_t i = 0; i < g.size[0]; ++i) {
                const Vec3d index{static_cast<double>(i), static_cast<double>(j),
                                  static_cast<double>(k)};
                double value = 0.0;
                for (const Vec3d& o : offsets) value += eroded(g.physical_from_index(index + o));
                value /= double(offsets.size());
                if (edit.noise_sigma > 0) value += noise(random);
                out.voxels[g.offset(i, j, k)] = static_cast<float>(value);
            }
    }
    return out;
}

std::string edit_json(const VolumeEdit& edit) {
    std::ostringstream s;
    const Eigen::Matrix4d m = edit.moved_from_original.matrix();
    s << "{\n  \"moved_from_original\": [";
    for (int r = 0; r < 4; ++r) {
        char row[128];
        std::snprintf(row, sizeof row, "%s[%.12g, %.12g, %.12g, %.12g]", r ? ", " : "", m(r, 0),
                      m(r, 1), m(r, 2), m(r, 3));
        s << row;
    }
    s << "],\n  \"erosions\": [";
    for (std::size_t n = 0; n < edit.erosions.size(); ++n) {
        const Erosion& e = edit.erosions[n];
        s << (n ? ", " : "") << "{\"center_original\": " << vec(e.center)
          << ", \"center_moved\": " << vec(edit.moved_from_original * e.center)
          << ", \"radius\": " << e.radius << ", \"value\": " << e.value << "}";
    }
    s << "],\n  \"voxel_size\": " << (edit.spacing ? vec(*edit.spacing) : "null")
      << ",\n  \"noise_sigma\": " << edit.noise_sigma << ",\n  \"noise_seed\": " << edit.noise_seed
      << "\n}\n";
    return s.str();
}

}  // namespace glint
