// The whole analysis with the sweep's GPU path (scanner/gpu_sweep.h) against the read-back
// path on the same device (lavapipe here): the decision must not depend on where the
// comparison ran.
#include "analysis/analysis.h"

#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "tests/scanner/dented_pair.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace glint {
namespace {

TEST(GpuAnalysis, DecidesTheSameRegionsAsTheReadBackPath) {
    const test::DentedPair& p = test::dented_pair();
    AnalysisOptions o;
    o.fit.mode = FitMode::Identity;
    o.sweep = test::small_vulkan_sweep(Accumulation::Auto);  // no output folder: the GPU path
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
