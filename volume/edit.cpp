#include "volume/edit.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "volume/sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace glint {

namespace {

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

// Whether the output's fractional index x maps inside the input's field of view (its voxels'
// extent, half a voxel beyond the outer centres); `over` receives, per input axis, how far it
// lies beyond (0: inside).
bool maps_inside(const VolumeGeometry& out, const VolumeGeometry& in,
                 const Rigid& original_from_moved, const Vec3d& x, Vec3d& over) {
    const Vec3d i = in.index_from_physical(original_from_moved * out.physical_from_index(x));
    for (Eigen::Index d = 0; d < 3; ++d) {
        const double last = double(in.size[static_cast<std::size_t>(d)] - 1) + 0.5;
        over[d] = i[d] < -0.5 ? i[d] + 0.5 : i[d] > last ? i[d] - last : 0.0;
    }
    return over.isZero();
}

// The output grid cropped to the field of view the input saw: the largest box of whole output
// voxels (grown by `reach`, the sub-samples' spread) whose every sample maps inside the input.
// Moving the object takes parts of it out of the input's field of view; a scan of the moved
// object has no data there (not air), so its surface ends open at its own field of view as the
// input's does. Shrinks one face at a time, the face of an outside corner along the output
// axis that moves furthest along the input axis it left. 	hrow InputError nothing is left.
VolumeGeometry crop_to_field_of_view(const VolumeGeometry& out, const VolumeGeometry& in,
                                     const Rigid& original_from_moved, double reach) {
    std::array<long, 3> lo{0, 0, 0}, hi{};
    for (std::size_t d = 0; d < 3; ++d) hi[d] = static_cast<long>(out.size[d]) - 1;
    // d(input index) / d(output index): which output axis moves along which input axis.
    Eigen::Matrix3d along;
    for (Eigen::Index a = 0; a < 3; ++a)
        along.col(a) =
            in.index_from_physical(original_from_moved * out.physical_from_index(Vec3d::Unit(a))) -
            in.index_from_physical(original_from_moved * out.physical_from_index(Vec3d::Zero()));
    for (bool inside = false; !inside;) {
        inside = true;
        for (int c = 0; c < 8 && inside; ++c) {
            std::array<bool, 3> high{};
            Vec3d x;
            for (std::size_t d = 0; d < 3; ++d) {
                high[d] = (c >> d) & 1;
                x[static_cast<Eigen::Index>(d)] =
                    high[d] ? double(hi[d]) + reach : double(lo[d]) - reach;
            }
            Vec3d over;
            if (maps_inside(out, in, original_from_moved, x, over)) continue;
            inside = false;
            Eigen::Index e = 0;
            over.cwiseAbs().maxCoeff(&e);
            Eigen::Index a = 0;
            along.row(e).cwiseAbs().maxCoeff(&a);
            const auto d = static_cast<std::size_t>(a);
            high[d] ? --hi[d] : ++lo[d];
            if (lo[d] > hi[d])
                throw InputError(
                    "volume edit: the motion moves the object wholly out of the "
                    "volume's field of view, expected a motion that keeps part of "
                    "it in view");
        }
    }
    VolumeGeometry g = out;
    g.origin = out.physical_from_index(Vec3d(double(lo[0]), double(lo[1]), double(lo[2])));
    for (std::size_t d = 0; d < 3; ++d) g.size[d] = static_cast<std::size_t>(hi[d] - lo[d] + 1);
    return g;
}

}  // namespace

Volume edit_volume(const Volume& in, const VolumeEdit& edit) {
    // Every number of the edit is checked before any voxel: a NaN value became a bare `nan` in
    // the truth JSON and a volume of NaN (issue 52).
    check_erosions(edit.erosions, "volume edit");
    for (const auto& [x, what] :
         {std::pair{edit.noise_sigma, "noise σ"}, std::pair{edit.psf_fwhm, "the point-spread FWHM"},
          std::pair{edit.noise_correlation, "the noise's correlation"}})
        if (!(x >= 0 && std::isfinite(x)))
            throw InputError(std::string("volume edit: ") + what + " is " + std::to_string(x) +
                             "; expected a finite value ≥ 0");
    if (!edit.moved_from_original.matrix().allFinite())
        throw InputError("volume edit: the motion holds a number that is not finite");
    Volume out;
    const Rigid original_from_moved = edit.moved_from_original.inverse();
    // Sub-sample offsets (in output voxels): one at the centre, or 2 × 2 × 2 over the voxel.
    std::vector<Vec3d> offsets = {Vec3d::Zero()};
    if (edit.spacing) {
        offsets.clear();
        for (int c = 0; c < 8; ++c)
            offsets.emplace_back(c & 1 ? 0.25 : -0.25, c & 2 ? 0.25 : -0.25, c & 4 ? 0.25 : -0.25);
    }
    out.geometry = crop_to_field_of_view(output_grid(in.geometry, edit.spacing), in.geometry,
                                         original_from_moved, edit.spacing ? 0.25 : 0.0);
    out.stored_type = "float";
    const VolumeGeometry& g = out.geometry;
    out.voxels.resize(g.voxel_count());
    const float background = in.range()[0];
    const double ramp = in.geometry.spacing.mean();  // the erosion's partial-volume ramp
    auto eroded = [&](const Vec3d& x) {
        const Vec3d p = original_from_moved * x;
        return eroded_value(sample_trilinear(in, in.geometry.index_from_physical(p), background), p,
                            edit.erosions, ramp);
    };
    for (std::size_t k = 0; k < g.size[2]; ++k) {
        throw_if_cancelled();
        for (std::size_t j = 0; j < g.size[1]; ++j)
            for (std::size_t i = 0; i < g.size[0]; ++i) {
                const Vec3d index{static_cast<double>(i), static_cast<double>(j),
                                  static_cast<double>(k)};
                double value = 0.0;
                for (const Vec3d& o : offsets) value += eroded(g.physical_from_index(index + o));
                out.voxels[g.offset(i, j, k)] = static_cast<float>(value / double(offsets.size()));
            }
    }
    apply_scanner(out, {edit.psf_fwhm, edit.noise_sigma, edit.noise_correlation, edit.noise_seed});
    return out;
}

void check_erosions(std::span<const Erosion> erosions, const std::string& who) {
    for (std::size_t i = 0; i < erosions.size(); ++i) {
        const Erosion& e = erosions[i];
        const std::string where = who + ": erosion " + std::to_string(i + 1) + ": ";
        if (!e.center.allFinite() || !(e.radius > 0 && std::isfinite(e.radius)))
            throw InputError(where + "centre and radius must be finite and the radius > 0 mm");
        if (!std::isfinite(e.value))
            throw InputError(where + "the value eroded material takes is " +
                             std::to_string(e.value) + "; expected a finite value");
    }
}

float eroded_value(float value, const Vec3d& p, std::span<const Erosion> erosions, double ramp) {
    for (const Erosion& e : erosions) {
        const double d = (p - e.center).norm() - e.radius;
        const double w = std::clamp(0.5 - d / ramp, 0.0, 1.0);
        value += static_cast<float>(w) * (std::min(value, e.value) - value);
    }
    return value;
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
      << ",\n  \"noise_correlation\": " << edit.noise_correlation
      << ",\n  \"psf_fwhm\": " << edit.psf_fwhm << "\n}\n";
    return s.str();
}

}  // namespace glint
