#include "volume/edit.h"

#include "mesh/cancel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

Volume edit_volume(const Volume& in, const VolumeEdit& edit) {
    Volume out;
    out.geometry = in.geometry;
    out.stored_type = "float";
    const VolumeGeometry& g = in.geometry;
    out.voxels.resize(g.voxel_count());
    const float background = in.range()[0];
    const double ramp = g.spacing.mean();  // the erosion's partial-volume ramp: one voxel
    const Rigid original_from_moved = edit.moved_from_original.inverse();
    for (std::size_t k = 0; k < g.size[2]; ++k) {
        throw_if_cancelled();
        for (std::size_t j = 0; j < g.size[1]; ++j)
            for (std::size_t i = 0; i < g.size[0]; ++i) {
                const Vec3d p = original_from_moved *
                                g.physical_from_index(Vec3d(double(i), double(j), double(k)));
                float value = sample(in, g.index_from_physical(p), background);
                for (const Erosion& e : edit.erosions) {
                    const double d = (p - e.center).norm() - e.radius;
                    const double w = std::clamp(0.5 - d / ramp, 0.0, 1.0);
                    value += static_cast<float>(w) * (std::min(value, e.value) - value);
                }
                out.voxels[g.offset(i, j, k)] = value;
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
    s << "]\n}\n";
    return s.str();
}

}  // namespace glint
