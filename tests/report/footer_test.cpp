// What atlas.png carries to be cited alone (report/detail/footer.h): both inputs, the date,
// the fit and the floors with their sources; and the legend's lines of regions, which give a
// missing-surface region no depth (report/detail/legend.h).
#include "report/detail/footer.h"
#include "report/detail/legend.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

bool holds(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

AnalysisResult decided_result() {
    AnalysisResult r;
    r.unit = "mm";
    r.decisions.resize(1);
    ZoomDecision& d = r.decisions[0];
    d.rule = DecisionRule::Fused;
    d.scale.radius = 1.0;  // the normal floor is an angle
    d.normal.value = 8.12;
    d.normal.source = FloorSource::Measured;
    d.shape.value = 0.021;
    d.shape.source = FloorSource::Minimum;
    return r;
}

TEST(Footer, NamesInputsDateFitAndFloorsWithTheirSources) {
    AnalysisResult r = decided_result();
    r.fit.mode = FitMode::Register;
    r.fit.reference_from_examined = Rigid::Identity();
    r.fit.reference_from_examined.linear() =
        Eigen::AngleAxisd(2.5 * std::numbers::pi / 180.0, Vec3d::UnitZ()).toRotationMatrix();
    r.fit.reference_from_examined.translation() = Vec3d(3.0, -4.0, 0.0);
    r.fit.registration = RegistrationResult{.rms = 0.0312, .overlap = 0.97};
    const auto lines = detail::footer_lines(
        r, {.reference_name = "jaw.ply", .examined_name = "jaw_dent.ply", .date = "2026-11-26"});
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_TRUE(holds(lines[0], "reference jaw.ply")) << lines[0];
    EXPECT_TRUE(holds(lines[0], "examined jaw_dent.ply")) << lines[0];
    EXPECT_TRUE(holds(lines[0], "2026-11-26")) << lines[0];
    EXPECT_TRUE(holds(lines[1], "registered")) << lines[1];
    EXPECT_TRUE(holds(lines[1], "rotation 2.50\u00b0")) << lines[1];
    EXPECT_TRUE(holds(lines[1], "translation 5 mm (3, \u22124, 0)")) << lines[1];
    EXPECT_TRUE(holds(lines[1], "RMS 0.0312 mm")) << lines[1];
    EXPECT_TRUE(holds(lines[2], "normal 8.12\u00b0 (measured)")) << lines[2];
    EXPECT_TRUE(holds(lines[2], "shape 0.021 mm (minimum)")) << lines[2];

    r.fit = FitOutcome{};  // identity
    r.decisions[0].normal.source = FloorSource::Given;
    r.decisions[0].shape.source = FloorSource::Capped;
    const auto identity = detail::footer_lines(r, {.date = "d"});
    EXPECT_TRUE(holds(identity[1], "fit: identity")) << identity[1];
    EXPECT_FALSE(holds(identity[1], "rotation"));
    EXPECT_TRUE(holds(identity[2], "(given)")) << identity[2];
    EXPECT_TRUE(holds(identity[2], "(capped)")) << identity[2];
    EXPECT_TRUE(holds(identity[0], "reference (unnamed)")) << identity[0];

    r.fit.mode = FitMode::File;
    EXPECT_TRUE(holds(detail::footer_lines(r, {})[1], "given (fit file), rotation 0.00\u00b0"));
}

// Issue 51: a "normal floor 170°" was printed; past 90° two normals bound nothing a surface
// shows (an asymmetry run on a surface whose sides differ by nature), so it is named no floor.
TEST(Footer, NeverCallsANormalSpreadPast90DegreesAFloor) {
    AnalysisResult r = decided_result();
    r.decisions[0].normal.value = 170.0;
    const std::string line = detail::footer_lines(r, {})[2];
    EXPECT_TRUE(holds(line, "normals none (they differ by 170° by nature)")) << line;
    EXPECT_FALSE(holds(line, "normal 170")) << line;
}

TEST(Footer, AddsItsAreaBelowThePictureWithTheLinesDrawn) {
    const Canvas sheet = detail::canvas(300, 100);
    const std::vector<std::string> lines{"reference a.ply", "fit: identity", "floors"};
    const Canvas out = detail::with_footer(sheet, lines);
    EXPECT_EQ(out.width(), 300);
    EXPECT_EQ(out.height(), 100 + detail::footer_height(3));
    EXPECT_GE(detail::footer_height(3), 3 * 13);
    if (!detail::has_font()) GTEST_SKIP() << "no font: the footer is blank";
    // Each line's band holds text pixels (brighter than the background).
    int bright_rows = 0;
    for (int y = 101; y < out.height(); ++y) {
        bool bright = false;
        for (int x = 0; x < 300 && !bright; ++x) bright = out.value(x, y, 0) > 0.4f;
        bright_rows += bright;
    }
    EXPECT_GT(bright_rows, 3 * 6);
}

TEST(Legend, GivesAMissingSurfaceRegionItsAreaAndNoDepth) {
    const Region dent{.id = 3, .area = 12.3, .peak_depth = -0.41, .kind = RegionKind::Dent};
    EXPECT_EQ(detail::region_legend_line(dent, "mm"), "3  dent  \u22120.41 mm, 12.3 mm\u00b2");
    const Region gone{.id = 5,
                      .area = 2.1,
                      .peak_depth = -0.7,
                      .volume = -1.2,
                      .kind = RegionKind::MissingSurface};
    EXPECT_EQ(detail::region_legend_line(gone, "mm"), "5  missing surface, 2.1 mm\u00b2");
}

}  // namespace
}  // namespace glint
