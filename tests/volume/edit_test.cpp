// A known change applied to a volume (volume/edit.h), as the CT pair generator uses it: another
// scanner's voxel size over the same extent with each voxel the mean over its own extent, and
// each scan's own noise realisation; the surface stays where the object is.
#include "volume/edit.h"

#include "mesh/components.h"
#include "mesh/error.h"
#include "volume/phantom.h"
#include "volume/surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace glint {
namespace {

// A sphere of radius 10 mm on a 1 × 1 × 2 mm grid (CThead's voxel shape), 48 × 48 × 24 voxels.
Volume sphere_volume() {
    EllipsoidVolumeOptions o;
    o.radii = {10, 10, 10};
    o.grid.spacing = {1, 1, 2};
    o.grid.size = {48, 48, 24};
    o.grid.origin = {-23.5, -23.5, -23};
    return make_ellipsoid_volume(o);
}

double rms_off_sphere(const Mesh& m, double radius) {
    double sum2 = 0.0;
    for (const auto& p : m.positions) {
        const double d = p.cast<double>().norm() - radius;
        sum2 += d * d;
    }
    return std::sqrt(sum2 / double(m.vertex_count()));
}

TEST(EditVolume, AnotherVoxelSizeCoversTheSameExtentAndKeepsTheSurfaceInPlace) {
    const Volume in = sphere_volume();
    VolumeEdit edit;
    edit.spacing = Vec3d(0.8, 0.8, 0.8);
    const Volume out = edit_volume(in, edit);
    EXPECT_EQ(out.geometry.size[0], 59u);  // 47 mm / 0.8 = 58.75 → 58 steps, 59 voxels
    EXPECT_EQ(out.geometry.size[2], 58u);  // 46 mm / 0.8 = 57.5 → 57 steps, 58 voxels
    EXPECT_EQ(out.geometry.origin, in.geometry.origin);
    EXPECT_EQ(out.geometry.spacing, Vec3d(0.8, 0.8, 0.8));
    const Mesh before = extract_surface(in, {.iso = 500.0}).mesh;
    const Mesh after = extract_surface(out, {.iso = 500.0}).mesh;
    EXPECT_GT(after.vertex_count(), before.vertex_count());  // finer voxels, more triangles
    // Partial volume at the new size: the surface stays within a tenth of the coarse voxel.
    EXPECT_LT(rms_off_sphere(after, 10.0), 0.2);
    EXPECT_LT(rms_off_sphere(before, 10.0), 0.2);
}

TEST(EditVolume, AMovedObjectIsSeenOnlyWhereTheInputSawItAndItsSurfaceEndsOpenThere) {
    // A bar 60 mm long through a 48 mm field of view along x: the input's surface ends open at
    // x = ±23.5 (its outer voxels' centres). Moved 5 mm along +x, the new scan has data only
    // where the moved bar was seen: x ≥ −24 + 5 (the input's outer voxel reaches −24).
    EllipsoidVolumeOptions o;
    o.radii = {30, 8, 8};
    o.grid.spacing = {1, 1, 2};
    o.grid.size = {48, 48, 24};
    o.grid.origin = {-23.5, -23.5, -23};
    const Volume in = make_ellipsoid_volume(o);
    VolumeEdit edit;
    edit.moved_from_original = Rigid(Eigen::Translation3d(5, 0, 0));
    const Volume out = edit_volume(in, edit);
    EXPECT_EQ(out.geometry.size[0], 43u);  // x from −18.5 (index 5) to 23.5
    EXPECT_EQ(out.geometry.size[1], 48u);
    EXPECT_NEAR(out.geometry.origin.x(), -18.5, 1e-12);
    EXPECT_NEAR(out.geometry.origin.y(), -23.5, 1e-12);
    const auto border_at = [](const Mesh& m, double x) {
        const auto border = border_vertices(m);
        std::size_t n = 0;
        for (std::size_t v = 0; v < m.vertex_count(); ++v)
            n += border[v] && std::abs(m.positions[v].x() - x) < 0.6;
        return n;
    };
    const Mesh moved = extract_surface(out, {.iso = 500.0}).mesh;
    float lowest = 1e9f;
    for (const auto& p : moved.positions) lowest = std::min(lowest, p.x());
    EXPECT_NEAR(lowest, -18.5, 0.01);
    EXPECT_GT(border_at(moved, -18.5), 20u) << "open at its own field of view, not capped";
    // A turned object: the cropped grid's every voxel corner still maps inside the input.
    edit.moved_from_original = motion_about(
        Rigid(Eigen::AngleAxisd(0.1, Vec3d(0.3, 0.2, 1.0).normalized())), Vec3d::Zero());
    edit.spacing = Vec3d(0.8, 0.8, 0.8);
    const Volume turned = edit_volume(in, edit);
    const Rigid back = edit.moved_from_original.inverse();
    for (int c = 0; c < 8; ++c) {
        Vec3d x;
        for (int d = 0; d < 3; ++d)
            x[d] = (c >> d) & 1
                       ? double(turned.geometry.size[static_cast<std::size_t>(d)] - 1) + 0.25
                       : -0.25;
        const Vec3d i =
            in.geometry.index_from_physical(back * turned.geometry.physical_from_index(x));
        for (int d = 0; d < 3; ++d) {
            EXPECT_GE(i[d], -0.5 - 1e-9);
            EXPECT_LE(i[d], double(in.geometry.size[static_cast<std::size_t>(d)]) - 0.5 + 1e-9);
        }
    }
    EXPECT_LT(turned.geometry.size[0], 59u);
    // Moved wholly out of view: one clear error.
    edit.moved_from_original = Rigid(Eigen::Translation3d(100, 0, 0));
    EXPECT_THROW((void)edit_volume(in, edit), InputError);
}

TEST(EditVolume, NoiseIsEachScansOwnRealisation) {
    const Volume in = sphere_volume();
    VolumeEdit a;
    a.noise_sigma = 50.0;
    a.noise_seed = 1;
    VolumeEdit b = a;
    b.noise_seed = 2;
    const Volume na = edit_volume(in, a), nb = edit_volume(in, b), again = edit_volume(in, a);
    EXPECT_EQ(na.voxels, again.voxels);  // a seed is one realisation
    double sum = 0.0, sum2 = 0.0, cross = 0.0;
    for (std::size_t i = 0; i < in.voxels.size(); ++i) {
        const double da = na.voxels[i] - in.voxels[i], db = nb.voxels[i] - in.voxels[i];
        sum += da;
        sum2 += da * da;
        cross += da * db;
    }
    const double n = double(in.voxels.size());
    EXPECT_NEAR(sum / n, 0.0, 1.0);
    EXPECT_NEAR(std::sqrt(sum2 / n), 50.0, 1.0);
    EXPECT_LT(std::abs(cross / sum2), 0.02);  // two seeds: independent realisations
    // The noisy surface stays on the sphere on average, rougher than the clean one.
    const Mesh clean = extract_surface(in, {.iso = 500.0, .largest = true}).mesh;
    const Mesh noisy = extract_surface(na, {.iso = 500.0, .largest = true}).mesh;
    EXPECT_GT(rms_off_sphere(noisy, 10.0), rms_off_sphere(clean, 10.0));
    EXPECT_LT(rms_off_sphere(noisy, 10.0), 0.5);
}

TEST(EditVolume, RefusesAVoxelSizeThatIsNoSize) {
    const Volume in = sphere_volume();
    for (const Vec3d& bad : {Vec3d(0, 1, 1), Vec3d(1, -1, 1), Vec3d(1, 1, std::nan(""))}) {
        VolumeEdit edit;
        edit.spacing = bad;
        EXPECT_THROW((void)edit_volume(in, edit), InputError) << bad.transpose();
    }
    VolumeEdit tiny;
    tiny.spacing = Vec3d(1e-3, 1e-3, 1e-3);  // 10^13 voxels: over the budget, before any work
    EXPECT_THROW((void)edit_volume(in, tiny), InputError);
}

// Issue 52: --erode-to nan was accepted and the truth JSON held a bare nan.
TEST(EditVolume, RefusesNumbersThatAreNotFinite) {
    const Volume in = sphere_volume();
    const float nan = std::nanf("");
    for (const Erosion& bad : {Erosion{{0, 0, 10}, 3, nan}, Erosion{{0, 0, 10}, nan, 0},
                               Erosion{{nan, 0, 10}, 3, 0}, Erosion{{0, 0, 10}, -1, 0}}) {
        VolumeEdit edit;
        edit.erosions = {bad};
        try {
            (void)edit_volume(in, edit);
            ADD_FAILURE() << "accepted erosion at " << bad.center.transpose() << " r " << bad.radius
                          << " to " << bad.value;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("erosion 1"), std::string::npos) << e.what();
        }
    }
    VolumeEdit noisy;
    noisy.noise_sigma = std::nan("");
    EXPECT_THROW((void)edit_volume(in, noisy), InputError);
}

TEST(EditVolume, TheTruthFileRecordsTheAcquisition) {
    VolumeEdit edit;
    edit.spacing = Vec3d(0.8, 0.8, 0.8);
    edit.noise_sigma = 20;
    edit.noise_seed = 7;
    const std::string json = edit_json(edit);
    EXPECT_NE(json.find("\"voxel_size\": [0.8, 0.8, 0.8]"), std::string::npos) << json;
    EXPECT_NE(json.find("\"noise_sigma\": 20"), std::string::npos) << json;
    EXPECT_NE(json.find("\"noise_seed\": 7"), std::string::npos) << json;
    edit.psf_fwhm = 0.6;
    edit.noise_correlation = 0.3;
    const std::string blurred = edit_json(edit);
    EXPECT_NE(blurred.find("\"psf_fwhm\": 0.6"), std::string::npos) << blurred;
    EXPECT_NE(blurred.find("\"noise_correlation\": 0.3"), std::string::npos) << blurred;
}

TEST(EditVolume, TheScannersBlurKeepsTheSurfaceInPlaceAndABadWidthIsRefusedFirst) {
    const Volume in = sphere_volume();
    VolumeEdit edit;
    edit.spacing = Vec3d(0.8, 0.8, 0.8);
    edit.psf_fwhm = 1.2;
    const Volume out = edit_volume(in, edit);
    // A symmetric blur moves a flat edge's middle value nowhere; the sphere's curvature pulls
    // it in by about σ² / r = 0.26² / 10 mm.
    EXPECT_LT(rms_off_sphere(extract_surface(out, {.iso = 500.0}).mesh, 10.0), 0.2);
    edit.psf_fwhm = -0.5;
    EXPECT_THROW((void)edit_volume(in, edit), InputError);
    edit.psf_fwhm = 0.0;
    edit.noise_correlation = NAN;
    EXPECT_THROW((void)edit_volume(in, edit), InputError);
}

}  // namespace
}  // namespace glint
