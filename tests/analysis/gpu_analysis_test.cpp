// The whole analysis with the sweep's GPU path (scanner/gpu_sweep.h) against the read-back
// path on the same device (lavapipe here): the decision must not depend on where the
// comparison ran.
#include "analysis/analysis.h"

#include "mesh/damage.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace glint {
namespace {

/// The reference condyle and a re-tessellated examined one with a 0.4 mm dent.
struct Pair {
    Mesh reference = make_phantom(
        {.kind = PhantomKind::Condyle, .scheme = TessellationScheme::Ico, .resolution = 4});
    Mesh examined = [] {
        Mesh m = make_phantom(
            {.kind = PhantomKind::Condyle, .scheme = TessellationScheme::Uv, .resolution = 40});
        apply_damage(
            m, {DamageSpec{
                   .kind = DamageKind::Dent, .center = {10, 0, 3}, .radius = 2.5, .depth = 0.4}});
        return m;
    }();
};

const Pair& pair() {
    static const Pair p;
    return p;
}

SweepOptions vulkan_options(Accumulation accumulate) {
    SweepOptions o;
    o.plan.azimuth_step_deg = 60;
    o.plan.elevations_deg = {-30, 30};
    o.plan.size = 96;
    o.render.backend = Backend::Vulkan;
    // lavapipe, or the device GLINT_DEVICE names.
    if (std::getenv("GLINT_DEVICE") == nullptr) o.render.device = "llvmpipe";
    o.render.supersample = 2;
    o.accumulate = accumulate;
    return o;
}

TEST(GpuAnalysis, DecidesTheSameRegionsAsTheReadBackPath) {
    const Pair& p = pair();
    AnalysisOptions o;
    o.fit.mode = FitMode::Identity;
    o.sweep = vulkan_options(Accumulation::Auto);  // no output folder: the GPU path
    const AnalysisResult g = analyse(p.reference, p.examined, o);
    o.sweep.accumulate = Accumulation::Host;
    const AnalysisResult h = analyse(p.reference, p.examined, o);
    ASSERT_TRUE(g.sweep.on_gpu);
    ASSERT_FALSE(h.sweep.on_gpu);
    ASSERT_EQ(g.decisions.size(), h.decisions.size());
    const ZoomDecision& dg = g.decisions[0];
    const ZoomDecision& dh = h.decisions[0];
    ASSERT_EQ(dh.regions.regions.size(), 1u);  // the dent
    EXPECT_EQ(dg.regions.regions.size(), dh.regions.regions.size());
    EXPECT_EQ(dg.regions.region_of_vertex, dh.regions.region_of_vertex);
    EXPECT_EQ(dg.normal.value, dh.normal.value);
    EXPECT_EQ(dg.regions.regions[0].kind, dh.regions.regions[0].kind);
    EXPECT_NEAR(dg.regions.regions[0].max_value, dh.regions.regions[0].max_value, 1e-4);
}

}  // namespace
}  // namespace glint
