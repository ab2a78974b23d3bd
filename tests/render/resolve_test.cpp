// The CPU resolve of s×s sub-samples into one pixel (render/detail/resolve.cpp): footprint
// averaging, coverage, and the rule that a covered pixel always carries a unit normal.
#include "render/detail/backend.h"
#include "render/frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace glint {
namespace {

/// One output pixel resolved from s = 2: four sub-samples (normal xyz, depth), ids.
Frame resolve_one_pixel(const std::vector<float>& normal_depth,
                        const std::vector<std::uint32_t>& ids) {
    Frame f;
    f.width = 1;
    f.height = 1;
    f.normal.assign(3, -1.0f);
    f.primitive_id.assign(1, 0);
    f.depth.assign(1, -1.0f);
    f.coverage.assign(1, -1.0f);
    detail::resolve_rows(normal_depth.data(), ids.data(), 2, 0, 1, f);
    return f;
}

TEST(ResolveSamples, AveragesAndRenormalisesCoveredSubSamples) {
    const float c = std::sqrt(0.5f);
    // Two sub-samples facing +x and +z, two uncovered: the mean direction is (1,0,1)/√2.
    const Frame f = resolve_one_pixel({1, 0, 0, 2.0f, 0, 0, 1, 4.0f, 0, 0, 0, 0, 0, 0, 0, 0},
                                      {7, 8, kNoPrimitive, kNoPrimitive});
    ASSERT_TRUE(f.is_covered(0));
    EXPECT_FLOAT_EQ(f.coverage[0], 0.5f);
    EXPECT_NEAR(f.normal[0], c, 1e-6f);
    EXPECT_NEAR(f.normal[1], 0.0f, 1e-6f);
    EXPECT_NEAR(f.normal[2], c, 1e-6f);
    EXPECT_FLOAT_EQ(f.depth[0], 3.0f);
}

TEST(ResolveSamples, CancellingNormalsLeaveThePixelUncoveredNotZeroLength) {
    // A knife edge seen along its ridge: two sub-samples facing +x, two facing −x.
    const Frame f = resolve_one_pixel(
        {1, 0, 0, 1.0f, -1, 0, 0, 1.0f, 1, 0, 0, 1.0f, -1, 0, 0, 1.0f}, {1, 2, 1, 2});
    EXPECT_FALSE(f.is_covered(0));
    EXPECT_EQ(f.primitive_id[0], kNoPrimitive);
    EXPECT_EQ(f.depth[0], kNoDepth);
    EXPECT_EQ(f.normal[0], 0.0f);
}

TEST(ResolveSamples, NearlyCancellingNormalsStillGiveAUnitNormal) {
    // Opposite but not exactly: a direction exists, and the pixel carries it at unit length.
    const Frame f =
        resolve_one_pixel({1, 0, 0, 1.0f, -0.9f, 0.4359f, 0, 1.0f, 0, 0, 0, 0, 0, 0, 0, 0},
                          {1, 2, kNoPrimitive, kNoPrimitive});
    ASSERT_TRUE(f.is_covered(0));
    const float len = std::sqrt(f.normal[0] * f.normal[0] + f.normal[1] * f.normal[1] +
                                f.normal[2] * f.normal[2]);
    EXPECT_NEAR(len, 1.0f, 1e-5f);
}

}  // namespace
}  // namespace glint
