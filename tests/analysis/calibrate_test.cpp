// The paper's first use: a referential deformation sets the zoom; only larger deformations
// are flagged at it.
#include "analysis/calibrate.h"

#include "mesh/damage.h"
#include "mesh/error.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace glint {
namespace {

Mesh condyle() {
    return make_phantom(
        {.kind = PhantomKind::Condyle, .scheme = TessellationScheme::Ico, .resolution = 5});
}

Mesh dented(double radius, double depth) {
    Mesh m = condyle();
    apply_damage(
        m,
        {DamageSpec{
            .kind = DamageKind::Dent, .center = {0, -5.2, 4}, .radius = radius, .depth = depth}});
    return m;
}

AnalysisOptions analysis_options() {
    AnalysisOptions o;
    o.fit.mode = FitMode::Identity;
    o.sweep.plan.azimuth_step_deg = 45;
    o.sweep.plan.elevations_deg = {-20, 20};
    o.sweep.render.backend = Backend::Embree;
    o.sweep.render.supersample = 4;
    return o;
}

std::size_t regions_at(const Mesh& examined, const Calibration& c) {
    AnalysisOptions o = analysis_options();
    o.sweep.plan.footprints = {c.footprint};
    o.decision.threshold = c.threshold_deg;
    return analyse(condyle(), examined, o).decisions[0].regions.regions.size();
}

TEST(Calibrate, OnlyDeformationsLargerThanTheReferentialOneAreFlagged) {
    // Referential: a 0.2 mm dent of 1.5 mm radius.
    const Calibration c = calibrate(
        condyle(), dented(1.5, 0.2), analysis_options(),
        CalibrationOptions{.threshold_deg = 3.0, .finest = 0.05, .coarsest = 4.0, .step = 1.5},
        "dent 1.5 mm / 0.2 mm");
    ASSERT_TRUE(c.found);
    // Finer rungs show it, the calibration rung and coarser ones do not.
    ASSERT_GT(c.ladder.size(), 3u);
    EXPECT_GT(c.ladder.front().regions, 0u);
    std::printf("calibration footprint %.3f mm/px (threshold %.1f deg)\n", c.footprint,
                c.threshold_deg);
    // Dents on either side of the referential one, scaled by 1.5 in radius and depth (the
    // same shape, so the same slopes, over a larger or smaller footprint): the larger is
    // flagged at the calibrated zoom, the smaller is not — though it is a real, visible
    // deformation at the finest rung, so its absence is the calibration's doing.
    EXPECT_GE(regions_at(dented(2.25, 0.3), c), 1u);
    EXPECT_EQ(regions_at(dented(1.0, 0.133), c), 0u);
    EXPECT_EQ(regions_at(dented(1.5, 0.2), c), 0u);
    Calibration finest = c;
    finest.footprint = c.ladder.front().footprint;
    EXPECT_GE(regions_at(dented(1.0, 0.133), finest), 1u);
}

TEST(Calibrate, RejectsBadLadders) {
    EXPECT_THROW((CalibrationOptions{.finest = 2, .coarsest = 1}.validate()), InputError);
    EXPECT_THROW(CalibrationOptions{.step = 1.0}.validate(), InputError);
    EXPECT_THROW(CalibrationOptions{.threshold_deg = 0}.validate(), InputError);
}

}  // namespace
}  // namespace glint
