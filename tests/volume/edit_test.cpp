// A known change applied to a volume (volume/edit.h), as the CT pair generator uses it: another
// scanner's voxel size over the same extent with each voxel the mean over its own extent, and
// each scan's own noise realisation; the surface stays where the object is.
#include "volume/edit.h"

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

TEST(EditVolume, TheTruthFileRecordsTheAcquisition) {
    VolumeEdit edit;
    edit.spacing = Vec3d(0.8, 0.8, 0.8);
    edit.noise_sigma = 20;
    edit.noise_seed = 7;
    const std::string json = edit_json(edit);
    EXPECT_NE(json.find("\"voxel_size\": [0.8, 0.8, 0.8]"), std::string::npos) << json;
    EXPECT_NE(json.find("\"noise_sigma\": 20"), std::string::npos) << json;
    EXPECT_NE(json.find("\"noise_seed\": 7"), std::string::npos) << json;
}

}  // namespace
}  // namespace glint
