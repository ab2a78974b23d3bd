#include "scanner/compare.h"

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
    TestFrame ref{{0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0}, {5, 5, 0, 0}, {1, 1, 0, 0}, {7, 8, kNoPrimitiveId, kNoPrimitiveId}};
    TestFrame exa{{0, static_cast<float>(std::sin(tilt)), static_cast<float>(std::cos(tilt)), 0, 0, 0, 0, 0, 1, 0, 0, 0},
                  {5.25f, 0, 4, 0},
                  {1, 0, 1, 0},
                  {3, kNoPrimitiveId, 4, kNoPrimitiveId}};
    const DeviationMap d = compare_frames(ref.view(), exa.view(), CompareOptions{.compute_rgb = true});
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
    const double expected_rgb = (0.0 + std::abs(std::round(127.5 * std::sin(tilt) + 127.5) - 128.0) +
                                 std::abs(std::round(127.5 * std::cos(tilt) + 127.5) - 255.0)) / 3.0;
    EXPECT_NEAR(d.rgb_abs[0], expected_rgb, 1e-3);
}

TEST(CompareFrames, PartlyCoveredEdgePixelsAreNotCompared) {
    TestFrame ref{{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, {1, 1, 1, 1}, {1, 0.5f, 1, 1}, {0, 0, 0, 0}};
    TestFrame exa{{1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, {1, 1, 1, 1}, {1, 1, 1, 1}, {0, 0, 0, 0}};
    const DeviationMap d = compare_frames(ref.view(), exa.view());
    EXPECT_EQ(d.compared, 3u);
    EXPECT_TRUE(std::isnan(d.angle_deg[1]));
    EXPECT_NEAR(d.max_angle_deg, 90.0, 1e-4);
}

TEST(CompareFrames, RejectsFramesOfDifferentSize) {
    TestFrame a{{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {0, 0, 0, 0}};
    FrameView small{1, 1, std::span<const float>(a.normal).first(3), std::span<const std::uint32_t>(a.prim).first(1),
                    std::span<const float>(a.depth).first(1), std::span<const float>(a.coverage).first(1)};
    EXPECT_THROW((void)compare_frames(a.view(), small), InputError);
}

}  // namespace
}  // namespace glint
