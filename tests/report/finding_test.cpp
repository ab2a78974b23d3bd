// A region in words (report/finding.h, issue 51): its side and part by the anatomical axes when
// the space states them, which way it is best seen from, and one sentence with depth ± its
// uncertainty, area and volume.
#include "report/finding.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

Bounds box(const Vec3f& lo, const Vec3f& hi) {
    Bounds b;
    b.extend(lo);
    b.extend(hi);
    return b;
}

TEST(RegionPlace, NamesTheSidesTheCentroidLiesTowardsInAPatientSpace) {
    // LPS: +x left, +y posterior, +z superior.
    const Orientation lps = resolve_orientation(PatientSpace::LPS, "");
    Region r;
    r.centroid = {40, -30, 2};  // left, anterior, mid height
    r.view_direction = Vec3d(0, 0, 1);
    EXPECT_EQ(region_place(r, box({-50, -50, -50}, {50, 50, 50}), lps),
              "left, anterior part, best seen from superior");
    r.centroid = {1, 2, -3};
    r.view_direction = Vec3d::Zero();
    EXPECT_EQ(region_place(r, box({-50, -50, -50}, {50, 50, 50}), lps), "central part");
}

TEST(RegionPlace, UsesMeshAxesWhenNoSpaceIsKnown) {
    const Orientation plain = resolve_orientation(PatientSpace::Unknown, "");
    Region r;
    r.centroid = {-30, 0, 0};
    EXPECT_EQ(region_place(r, box({-50, -50, -50}, {50, 50, 50}), plain), "-x part");
}

TEST(RegionSentence, SaysDepthWithItsUncertaintyAreaAndVolume) {
    Region dent;
    dent.kind = RegionKind::Dent;
    dent.peak_depth = -1.734;
    dent.area = 26.9;
    dent.volume = -18.1;
    EXPECT_EQ(region_sentence(dent, "left part", 0.056, "mm"),
              "a dent 1.73 ± 0.056 mm deep over 26.9 mm² (18.1 mm³ lost), left part");
    Region bump = dent;
    bump.kind = RegionKind::Bump;
    bump.peak_depth = 0.5;
    bump.volume = 2.0;
    EXPECT_EQ(region_sentence(bump, "central part", 0.0, ""),
              "a bump 0.5 units high over 26.9 units² (2 units³ gained), central part");
    Region gone = dent;
    gone.kind = RegionKind::MissingSurface;
    EXPECT_EQ(region_sentence(gone, "right part", 0.05, "mm"),
              "missing surface over 26.9 mm² (the examined scan holds none there), right part");
    EXPECT_EQ(region_sentence(bump, "superior part", 0.91, "mm", true),
              "0.5 ± 0.91 mm more than the mirrored other side over 26.9 mm² (2 mm³ more), "
              "superior part");
    EXPECT_EQ(region_sentence(dent, "right part", 0.0, "mm", true),
              "1.73 mm less than the mirrored other side over 26.9 mm² (18.1 mm³ less), right "
              "part");
    Region resected = dent;  // surface gone where the examined surface covered around it
    resected.hole = true;
    resected.peak_depth = -93.4;
    resected.area = 7310.0;
    resected.volume = -23400.0;
    EXPECT_EQ(region_sentence(resected, "right part", 0.05, "mm"),
              "surface gone over 7310 mm² (about 23400 mm³ lost; it stood up to 93.4 mm above "
              "the rim of what remains), right part");
}

}  // namespace
}  // namespace glint
