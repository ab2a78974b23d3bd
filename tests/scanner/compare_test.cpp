#include "scanner/compare.h"
#include "scanner/metric.h"

#include "mesh/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

// A 2×2 frame: pixel 0 covered in both, 1 reference only, 2 examined only, 3 neither.
struct TestFrame {
    std::vector<float> normal, depth, coverage;
    std::vector<std::uint32_t> prim;
    FrameView view() const { return {2, 2, normal, prim, depth, coverage}; }
};

TEST(CompareFrames, MeasuresAngleSignedDepthAndSilhouette) {
    const double tilt = 10.0 * std::numbers::pi / 180.0;
    TestFrame ref{{0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0},
                  {5, 5, 0, 0},
                  {1, 1, 0, 0},
                  {7, 8, kNoPrimitive, kNoPrimitive}};
    TestFrame exa{{0, static_cast<float>(std::sin(tilt)), static_cast<float>(std::cos(tilt)), 0, 0,
                   0, 0, 0, 1, 0, 0, 0},
                  {5.25f, 0, 4, 0},
                  {1, 0, 1, 0},
                  {3, kNoPrimitive, 4, kNoPrimitive}};
    const DeviationMap d = compare_frames(ref.view(), exa.view(), CompareOptions{}, Metric::RgbAbs);
    EXPECT_EQ(d.compared, 1u);
    // Float normals: the angle is exact to ~1e-5° (float rounding of sin/cos).
    EXPECT_NEAR(d.angle_deg[0], 10.0, 1e-4);
    EXPECT_FLOAT_EQ(d.signed_depth[0], -0.25f);  // examined farther: a dent
    EXPECT_EQ(d.silhouette[1], static_cast<std::uint8_t>(Silhouette::ReferenceOnly));
    EXPECT_EQ(d.silhouette[2], static_cast<std::uint8_t>(Silhouette::ExaminedOnly));
    EXPECT_TRUE(std::isnan(d.angle_deg[3]));
    EXPECT_EQ(d.reference_only, 1u);
    EXPECT_EQ(d.examined_only, 1u);
    // Paper metric: |Δ(0.5·n)|·255 averaged over R, G, B, on 8-bit colours.
    const double expected_rgb =
        (0.0 + std::abs(std::round(127.5 * std::sin(tilt) + 127.5) - 128.0) +
         std::abs(std::round(127.5 * std::cos(tilt) + 127.5) - 255.0)) /
        3.0;
    EXPECT_NEAR(d.value[0], expected_rgb, 1e-3);
    EXPECT_TRUE(std::isnan(d.value[3]));
}

TEST(CompareFrames, PartlyCoveredEdgePixelsAreNotCompared) {
    TestFrame ref{
        {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, {1, 1, 1, 1}, {1, 0.5f, 1, 1}, {0, 0, 0, 0}};
    TestFrame exa{{1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, {1, 1, 1, 1}, {1, 1, 1, 1}, {0, 0, 0, 0}};
    const DeviationMap d = compare_frames(ref.view(), exa.view());
    EXPECT_EQ(d.compared, 3u);
    EXPECT_TRUE(std::isnan(d.angle_deg[1]));
    EXPECT_NEAR(d.max_angle_deg, 90.0, 1e-4);
}

TEST(CompareFrames, RejectsFramesOfDifferentSize) {
    TestFrame a{{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {0, 0, 0, 0}};
    FrameView small{1,
                    1,
                    std::span<const float>(a.normal).first(3),
                    std::span<const std::uint32_t>(a.prim).first(1),
                    std::span<const float>(a.depth).first(1),
                    std::span<const float>(a.coverage).first(1)};
    EXPECT_THROW((void)compare_frames(a.view(), small), InputError);
}

TEST(Metrics, EveryDescriptorIsCompleteAndParsesByName) {
    // A metric is one descriptor: everything downstream (atlas names, report keys, picture
    // titles, histogram, colour scale) reads it, so an incomplete one would break them all.
    ASSERT_GE(metrics().size(), 2u);
    for (const auto& m : metrics()) {
        EXPECT_FALSE(m.name.empty());
        EXPECT_FALSE(m.unit.empty());
        EXPECT_FALSE(m.title.empty());
        EXPECT_GT(m.max_value, 0.0);
        EXPECT_GT(m.missing_value, 0.0f);
        EXPECT_LE(m.missing_value, m.max_value);
        EXPECT_GT(m.histogram_bin, 0.0);
        EXPECT_GT(m.histogram_max, m.histogram_bin);
        EXPECT_GT(m.color_max, 0.0);
        ASSERT_NE(m.compute, nullptr);
        EXPECT_EQ(parse_metric(m.name), m.id);
        EXPECT_EQ(&describe(m.id), &m);
    }
    try {
        (void)parse_metric("hsv");
        FAIL() << "an unknown metric was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("angle or rgb"), std::string::npos) << e.what();
    }
}

TEST(Metrics, AngleMetricValuesAreTheComparedAngles) {
    TestFrame ref{{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {0, 0, 0, 0}};
    TestFrame exa{{1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {0, 0, 0, 0}};
    const DeviationMap d =
        compare_frames(ref.view(), exa.view(), CompareOptions{}, Metric::AngleDeg);
    ASSERT_EQ(d.value.size(), 4u);
    EXPECT_NEAR(d.value[0], 90.0, 1e-4);
    EXPECT_NEAR(d.value[1], 0.0, 1e-4);
}

}  // namespace
}  // namespace glint
