// Where a volume places its iso-surface firmly (volume/contrast.h): a ball whose one side meets
// tissue just below the iso value (faint) and whose other side meets air (firm), under a known
// noise; the noise estimate; and the field of view an extracted surface carries.
#include "volume/contrast.h"

#include "volume/edit.h"
#include "volume/phantom.h"
#include "volume/surface.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace glint {
namespace {

// A ball of radius 8 (inside 1000, air 0, iso 500) in 32³ unit voxels; on the side x > 2 the
// air is replaced by tissue at 480, 20 below the iso value; noise σ = 20 added.
Volume ball_beside_tissue() {
    EllipsoidVolumeOptions o;
    o.radii = {8, 8, 8};
    o.grid.size = {32, 32, 32};
    o.grid.spacing = {1, 1, 1};
    o.grid.origin = {-15.5, -15.5, -15.5};
    Volume v = make_ellipsoid_volume(o);
    const auto& g = v.geometry;
    for (std::size_t k = 0; k < g.size[2]; ++k)
        for (std::size_t j = 0; j < g.size[1]; ++j)
            for (std::size_t i = 0; i < g.size[0]; ++i) {
                const Vec3d p = g.physical_from_index(Vec3d(double(i), double(j), double(k)));
                float& x = v.voxels[g.offset(i, j, k)];
                if (p.x() > 2.0) x = std::max(x, 480.0f);
            }
    VolumeEdit noise;
    noise.noise_sigma = 20.0;
    noise.noise_seed = 7;
    return edit_volume(v, noise);
}

TEST(Contrast, TheNoiseEstimateFindsTheNoiseAdded) {
    const double sigma = noise_sigma(ball_beside_tissue());
    EXPECT_NEAR(sigma, 20.0, 3.0);
    EllipsoidVolumeOptions o;
    o.grid.size = {24, 24, 24};
    o.grid.origin = {-11.5, -11.5, -11.5};
    EXPECT_LT(noise_sigma(make_ellipsoid_volume(o)), 1.0) << "a noiseless phantom";
}

TEST(Contrast, SurfaceBesideTissueNearTheIsoValueIsFaintAndBesideAirFirm) {
    const Volume v = ball_beside_tissue();
    const ExtractedSurface s = extract_surface(v, {.iso = 500.0, .largest = true});
    ASSERT_EQ(s.mesh.faint.size(), s.mesh.vertex_count());
    EXPECT_NEAR(s.report.noise_sigma, 20.0, 3.0);
    std::size_t air = 0, air_faint = 0, tissue = 0, tissue_faint = 0;
    for (std::size_t u = 0; u < s.mesh.vertex_count(); ++u) {
        const float x = s.mesh.positions[u].x();
        if (x < -2) {
            ++air;
            air_faint += s.mesh.faint[u];
        } else if (x > 4) {
            ++tissue;
            tissue_faint += s.mesh.faint[u];
        }
    }
    ASSERT_GT(air, 100u);
    ASSERT_GT(tissue, 100u);
    EXPECT_LT(double(air_faint), 0.02 * double(air));
    EXPECT_GT(double(tissue_faint), 0.9 * double(tissue));
    // With the band narrowed below the tissue's offset, that side is firm too.
    const auto narrow = faint_vertices(v, s.mesh, 500.0, 5.0);
    EXPECT_LT(std::count(narrow.begin(), narrow.end(), 1),
              static_cast<std::ptrdiff_t>(tissue_faint / 4));
}

TEST(Contrast, AnExtractedSurfaceCarriesItsGridAndRoiAsItsFieldOfView) {
    EllipsoidVolumeOptions o;
    o.radii = {8, 8, 8};
    o.grid.size = {32, 32, 32};
    o.grid.origin = {-15.5, -15.5, -15.5};
    SurfaceOptions so{.iso = 500.0};
    so.roi = Roi{.shape = Roi::Shape::Box, .min = {-20, -20, -20}, .max = {20, 20, 3}};
    const Mesh m = extract_surface(make_ellipsoid_volume(o), so).mesh;
    ASSERT_EQ(m.field_of_view.boxes.size(), 2u);
    EXPECT_NEAR(m.field_of_view.depth_inside(Vec3d(0, 0, 0)), 3.0, 1e-9);      // the ROI's top
    EXPECT_NEAR(m.field_of_view.depth_inside(Vec3d(0, 0, -14.5)), 1.0, 1e-9);  // the grid's end
    EXPECT_LT(m.field_of_view.depth_inside(Vec3d(0, 0, 5)), 0.0);
}

}  // namespace
}  // namespace glint
