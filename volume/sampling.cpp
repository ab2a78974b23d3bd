#include "volume/sampling.h"

#include <algorithm>
#include <array>

namespace glint {

float sample_trilinear(const Volume& v, const Vec3d& index, float outside) {
    const VolumeGeometry& g = v.geometry;
    std::array<std::size_t, 3> i0{};
    std::array<double, 3> f{};
    for (std::size_t d = 0; d < 3; ++d) {
        const double last = double(g.size[d] - 1);
        double x = index[static_cast<Eigen::Index>(d)];
        if (!(x >= -0.5) || x > last + 0.5) return outside;
        x = std::clamp(x, 0.0, last);
        i0[d] = g.size[d] < 2 ? 0 : std::min(static_cast<std::size_t>(x), g.size[d] - 2);
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

}  // namespace glint
