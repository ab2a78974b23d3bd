// Floors that stay honest on rough surfaces (decision/decision.h EvidenceScale): two noisy
// acquisitions of one 10 mm sphere, each with its own noise (σ = 0.1 mm along the normals,
// as CT staircase noise, different tessellations), differ everywhere beyond the plausible
// floors. The run must not cap and report the noise as dozens of regions: it reads the evidence
// at a scale where the undamaged majority is quiet, says which and what it can detect there,
// and finds a real 1 mm dent there.
#include "analysis/analysis.h"

#include "mesh/damage.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace glint {
namespace {

Mesh rough_sphere(TessellationScheme scheme, int resolution, std::uint32_t seed) {
    Mesh m =
        make_phantom({.kind = PhantomKind::Sphere, .scheme = scheme, .resolution = resolution});
    apply_damage(m, {DamageSpec{.kind = DamageKind::Noise, .sigma = 0.1, .seed = seed}});
    return m;
}

AnalysisOptions rough_options() {
    AnalysisOptions o;
    o.fit.mode = FitMode::Identity;
    o.sweep.plan.azimuth_step_deg = 45;
    o.sweep.plan.elevations_deg = {-60, 0, 60};
    o.sweep.plan.footprints = {0.1};
    o.sweep.render.backend = Backend::Embree;
    return o;
}

TEST(RoughSurface, WithoutDamageTheMajorityIsQuietAtAChosenScaleAndNothingIsReported) {
    const Mesh ref = rough_sphere(TessellationScheme::Ico, 5, 1);
    const Mesh exa = rough_sphere(TessellationScheme::Uv, 80, 2);
    const AnalysisResult r = analyse(ref, exa, rough_options());
    const ZoomDecision& d = r.decisions[0];
    EXPECT_TRUE(d.scale.searched) << "the floors at the vertices' own scale were plausible";
    EXPECT_TRUE(d.scale.quiet);
    EXPECT_GT(d.scale.radius, 0.0);
    EXPECT_FALSE(d.normal.implausible);
    EXPECT_FALSE(d.shape.implausible);
    EXPECT_TRUE(d.scale.own_normal.implausible || d.scale.own_shape.implausible);
    EXPECT_EQ(d.regions.regions.size(), 0u);
    // What it can detect there, stated in mm and mm².
    EXPECT_GT(d.scale.min_depth, 0.0);
    EXPECT_LT(d.scale.min_depth, 1.0);
    EXPECT_GT(d.scale.min_area, 0.0);
    EXPECT_NE(d.scale.text.find("mm deep over"), std::string::npos) << d.scale.text;
    bool warned = false;
    for (const auto& w : r.warnings) warned |= w.find("read over a radius of") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(RoughSurface, ADentWiderThanTheScaleIsFoundAndNothingElse) {
    const Mesh ref = rough_sphere(TessellationScheme::Ico, 5, 1);
    Mesh exa = rough_sphere(TessellationScheme::Uv, 80, 2);
    // note: on the equator: at the UV sphere's poles the noisy fan of thin triangles makes the
    // tessellation tolerance (½·h·θ) larger than the dent.
    apply_damage(
        exa,
        {DamageSpec{.kind = DamageKind::Dent, .center = {0, 10, 0}, .radius = 3.5, .depth = 1.0}});
    const AnalysisResult r = analyse(ref, exa, rough_options());
    const ZoomDecision& d = r.decisions[0];
    EXPECT_TRUE(d.scale.quiet);
    ASSERT_EQ(d.regions.regions.size(), 1u)
        << d.rule_text << "; " << d.scale.text << "; normal " << d.normal.value << " low "
        << d.normal.low << "; shape " << d.shape.value << " low " << d.shape.low << "; damaged "
        << d.regions.damaged_vertices << ", dropped " << d.regions.dropped_small;
    const Region& g = d.regions.regions[0];
    EXPECT_EQ(g.kind, RegionKind::Dent);
    EXPECT_LT((g.centroid - Vec3d(0, 10, 0)).norm(), 1.5);
    EXPECT_LT(g.peak_depth, -0.5);
}

}  // namespace
}  // namespace glint
