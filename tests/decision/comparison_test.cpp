// What both surfaces can compare (decision/comparison.h) on a flat grid with unit edges: the
// reference's own border band, a part the examined surface did not reach and the band along
// its border, a hole inside covered surface and the direction of the surface gone there; and
// decide() on them: no region where nothing was compared, a loss where worn-away surface left
// a hole.
#include "decision/comparison.h"
#include "decision/decision.h"

#include "scanner/atlas.h"
#include "scanner/coverage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

constexpr int kN = 40;

std::size_t vid(int x, int y) { return static_cast<std::size_t>(y * (kN + 1) + x); }

// A kN × kN grid of unit squares; z(x, y) lifts it.
template <class Height>
Mesh grid(Height z) {
    Mesh m;
    for (int y = 0; y <= kN; ++y)
        for (int x = 0; x <= kN; ++x)
            m.positions.emplace_back(float(x), float(y), static_cast<float>(z(x, y)));
    for (int y = 0; y < kN; ++y)
        for (int x = 0; x < kN; ++x) {
            const auto a = static_cast<std::uint32_t>(vid(x, y)),
                       b = static_cast<std::uint32_t>(vid(x + 1, y)),
                       c = static_cast<std::uint32_t>(vid(x + 1, y + 1)),
                       d = static_cast<std::uint32_t>(vid(x, y + 1));
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
        }
    m.normals.assign(m.positions.size(), Vec3f(0, 0, 1));
    return m;
}

Mesh flat() {
    return grid([](int, int) { return 0.0; });
}

struct Inputs {
    std::size_t n = (kN + 1) * (kN + 1);
    std::vector<std::uint8_t> seen = std::vector<std::uint8_t>(n, 1);
    std::vector<float> missing = std::vector<float>(n, 0.0f);
    std::vector<float> distance = std::vector<float>(n, 0.0f);
    std::vector<std::uint8_t> at_border = std::vector<std::uint8_t>(n, 0);
    [[nodiscard]] ComparisonInputs view() const {
        return {.seen = &seen, .missing = &missing, .distance = &distance, .at_border = &at_border};
    }
    // No examined surface on the disc of `radius` around (cx, cy).
    void gone(int cx, int cy, double radius) {
        for (int y = 0; y <= kN; ++y)
            for (int x = 0; x <= kN; ++x)
                if (std::hypot(x - cx, y - cy) <= radius) missing[vid(x, y)] = 1.0f;
    }
};

CompareClass class_at(const Comparison& c, int x, int y) {
    return static_cast<CompareClass>(c.vertex_class[vid(x, y)]);
}

TEST(Comparison, KeepsABandAlongTheReferencesBorderOutOfTheComparison) {
    const Inputs in;
    const Comparison c = classify_comparison(flat(), in.view());
    EXPECT_DOUBLE_EQ(c.edge, 1.0);
    EXPECT_DOUBLE_EQ(c.band, kBandEdges);
    EXPECT_EQ(class_at(c, 0, 20), CompareClass::ReferenceBorder);
    EXPECT_EQ(class_at(c, 4, 20), CompareClass::ReferenceBorder);
    EXPECT_EQ(class_at(c, 5, 20), CompareClass::Compared);
    EXPECT_EQ(class_at(c, 20, 20), CompareClass::Compared);
    // 31 × 31 vertices (5 … 35) with a unit dual area each, of 40 × 40.
    EXPECT_NEAR(c.fraction, 31.0 * 31.0 / (40.0 * 40.0), 1e-6);
    EXPECT_NEAR(c.compared_area + c.reference_border_area, c.reference_area, 1e-9);
    EXPECT_EQ(c.holes, 0u);
}

TEST(Comparison, APartialScanIsNotReachedAndItsBorderIsBanded) {
    Inputs in;
    // The examined scan stops at x = 20: beyond it the closest examined point is on its border.
    for (int y = 0; y <= kN; ++y)
        for (int x = 21; x <= kN; ++x) {
            in.at_border[vid(x, y)] = 1;
            in.distance[vid(x, y)] = static_cast<float>(x - 20);
        }
    const Comparison c = classify_comparison(flat(), in.view());
    EXPECT_EQ(class_at(c, 30, 20), CompareClass::NotReached);
    EXPECT_EQ(class_at(c, 17, 20), CompareClass::ExaminedBorder);
    EXPECT_EQ(class_at(c, 15, 20), CompareClass::Compared);
    EXPECT_EQ(c.holes, 0u);
    EXPECT_NEAR(c.not_reached_area / c.reference_area, 0.5, 0.05);
    EXPECT_LT(c.fraction, 0.4);
}

TEST(Comparison, AHoleInsideCoveredSurfaceStaysComparedAndAWornCapIsALoss) {
    // A cap of height 2 on the flat grid, its top (r ≤ 3) gone from the examined surface.
    const auto cap = [](int x, int y) {
        return std::max(0.0, 2.0 - 0.25 * std::hypot(x - 20, y - 20));
    };
    Inputs in;
    in.gone(20, 20, 3.0);
    const Comparison c = classify_comparison(grid(cap), in.view());
    EXPECT_EQ(c.holes, 1u);
    EXPECT_EQ(class_at(c, 20, 20), CompareClass::Compared);
    EXPECT_TRUE(c.in_hole[vid(20, 20)]);
    EXPECT_LT(c.hole_depth[vid(20, 20)], -0.5f);  // the top stood above the hole's rim
    EXPECT_TRUE(c.hole_loss[vid(20, 20)]);
    EXPECT_EQ(c.lost_holes, 1u);
    EXPECT_DOUBLE_EQ(c.lost_hole_area, c.hole_area);
    // A hole over a pit: nothing stood above its rim (depth 0), but an examined surface that is
    // no one-view scan cannot drop out, so the surface gone there is material gone: a loss.
    const auto pit = [&](int x, int y) { return -cap(x, y); };
    const Comparison p = classify_comparison(grid(pit), in.view());
    EXPECT_EQ(p.holes, 1u);
    EXPECT_EQ(p.hole_depth[vid(20, 20)], 0.0f);
    EXPECT_TRUE(p.hole_loss[vid(20, 20)]);
    EXPECT_EQ(p.lost_holes, 1u);
    // On a one-view scan that faced the pit (a hole, not a grazing dropout) the rim cannot tell
    // worn-away material from a dropout: no loss, depth unknown (0).
    const ScanView facing{.direction = Vec3d(0.0, 0.0, 1.0), .cone_deg = 77.0};
    ComparisonInputs one_view = in.view();
    one_view.scan_view = &facing;
    const Comparison q = classify_comparison(grid(pit), one_view);
    EXPECT_EQ(q.holes, 1u);
    EXPECT_EQ(q.dropouts, 0u);
    EXPECT_EQ(q.hole_depth[vid(20, 20)], 0.0f);
    EXPECT_FALSE(q.hole_loss[vid(20, 20)]);
    EXPECT_EQ(q.lost_holes, 0u);
    // The worn cap stays a loss on that scan: the reference stood above the hole's rim.
    EXPECT_TRUE(classify_comparison(grid(cap), one_view).hole_loss[vid(20, 20)]);
}

TEST(Comparison, AGonePartReachingBeyondTheExaminedFieldOfViewIsNotReachedNeverAHole) {
    // The worn cap of the hole test, but the examined scan's field of view ends at x = 21 (a
    // skull's dome cut by the scan's last slice: reached surface all round the gone top).
    const auto cap = [](int x, int y) {
        return std::max(0.0, 2.0 - 0.25 * std::hypot(x - 20, y - 20));
    };
    Inputs in;
    in.gone(20, 20, 3.0);
    std::vector<std::uint8_t> beyond(in.n, 0);
    for (int y = 0; y <= kN; ++y)
        for (int x = 22; x <= kN; ++x) beyond[vid(x, y)] = 1;
    ComparisonInputs view = in.view();
    view.beyond_view = &beyond;
    const Comparison c = classify_comparison(grid(cap), view);
    EXPECT_EQ(c.holes, 0u);
    EXPECT_EQ(c.beyond_view, 1u);
    EXPECT_GT(c.beyond_view_area, 20.0);
    EXPECT_EQ(class_at(c, 20, 20), CompareClass::NotReached);
    EXPECT_FALSE(c.in_hole[vid(20, 20)]);
    EXPECT_EQ(class_at(c, 20, 10), CompareClass::Compared) << "reached surface stays compared";
    // A field of view that holds the whole gone part leaves it a hole.
    std::fill(beyond.begin(), beyond.end(), 0);
    for (int y = 0; y <= kN; ++y) beyond[vid(kN, y)] = 1;
    EXPECT_EQ(classify_comparison(grid(cap), view).holes, 1u);
}

TEST(Comparison, AOneViewScansDropoutAtGrazingIncidenceIsNotReachedNotAHole) {
    // The same gone disc on the flat grid (normals +z), the examined surface a one-view scan.
    Inputs in;
    in.gone(20, 20, 3.0);
    const auto classify = [&](double view_deg) {
        const double a = view_deg * std::numbers::pi / 180.0;
        const ScanView view{.direction = Vec3d(std::sin(a), 0.0, std::cos(a)), .cone_deg = 77.0};
        ComparisonInputs inputs = in.view();
        inputs.scan_view = &view;
        return classify_comparison(flat(), inputs);
    };
    // Seen at 75° incidence (beyond kGrazingDeg): a scanner's dropout, not reached.
    const Comparison grazing = classify(75.0);
    EXPECT_EQ(grazing.holes, 0u);
    EXPECT_EQ(grazing.dropouts, 1u);
    EXPECT_NEAR(grazing.dropout_area, 29.0, 1e-9);  // 29 vertices of unit dual area
    EXPECT_EQ(class_at(grazing, 20, 20), CompareClass::NotReached);
    EXPECT_EQ(class_at(grazing, 20, 25), CompareClass::ExaminedBorder);
    ASSERT_TRUE(grazing.scan_view.has_value());
    // Faced at 45°: the scanner saw it well, so the surface is really gone there: a hole.
    const Comparison facing = classify(45.0);
    EXPECT_EQ(facing.holes, 1u);
    EXPECT_EQ(facing.dropouts, 0u);
    EXPECT_EQ(class_at(facing, 20, 20), CompareClass::Compared);
    // No one-view scan: a hole, as before.
    EXPECT_EQ(classify_comparison(flat(), in.view()).holes, 1u);
}

TEST(Comparison, ALargePartWithoutExaminedSurfaceIsNotReachedEvenAwayFromBorders) {
    Inputs in;
    in.gone(20, 20, 13.0);  // about 33 % of the area: more than a hole
    const Comparison c = classify_comparison(flat(), in.view());
    EXPECT_EQ(c.holes, 0u);
    EXPECT_EQ(class_at(c, 20, 20), CompareClass::NotReached);
    EXPECT_EQ(class_at(c, 20, 35), CompareClass::ExaminedBorder);
    in.missing.assign(in.n, 0.0f);
    in.gone(20, 20, 11.0);  // about 24 %: a hole (three worn cusps take 14 % of a crown)
    EXPECT_EQ(classify_comparison(flat(), in.view()).holes, 1u);
}

// An examined surface that encloses its solid holds surface wherever the object has some: the
// same third of the surface without it is gone (a resection), up to half of it; beyond that the
// examined surface is a part of the reference, and what it lacks not reached.
TEST(Comparison, WhatAnEnclosingExaminedSurfaceLacksIsGoneUpToHalfTheReference) {
    Inputs in;
    in.gone(20, 20, 13.0);  // about 33 %
    ComparisonInputs enclosing = in.view();
    enclosing.examined_encloses = true;
    const Comparison c = classify_comparison(flat(), enclosing);
    EXPECT_TRUE(c.examined_encloses);
    EXPECT_EQ(c.holes, 1u);
    EXPECT_EQ(c.lost_holes, 1u);
    EXPECT_EQ(class_at(c, 20, 20), CompareClass::Compared);
    EXPECT_EQ(c.in_hole[vid(20, 20)], 1);
    EXPECT_EQ(c.hole_loss[vid(20, 20)], 1);
    in.missing.assign(in.n, 0.0f);
    in.gone(20, 20, 17.0);  // about 57 %: a part, not a loss
    enclosing = in.view();
    enclosing.examined_encloses = true;
    const Comparison part = classify_comparison(flat(), enclosing);
    EXPECT_EQ(part.holes, 0u);
    EXPECT_EQ(class_at(part, 20, 20), CompareClass::NotReached);
}

// Whether a surface encloses its solid: a closed one does, one with a small opening does, a
// patch does not.
TEST(Comparison, ASurfaceEnclosesItsSolidWhenItsBordersAreShort) {
    EXPECT_FALSE(encloses(flat()));  // 160 units of border against √1600 = 40
    Mesh box;                        // a closed cube, outward
    box.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    box.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                     {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    EXPECT_TRUE(encloses(box));
    box.triangles.pop_back();  // one triangle out: 3.4 units of border against 0.2·√5.5
    EXPECT_FALSE(encloses(box));
}

// An open tube (two scans' fields of view end at its rims): 24 vertices round, 41 rings of unit
// height, about unit edges.
Mesh tube() {
    constexpr int kRound = 24, kRings = 41;
    const double r = kRound / (2.0 * 3.14159265358979);
    Mesh m;
    for (int z = 0; z < kRings; ++z)
        for (int k = 0; k < kRound; ++k) {
            const double a = 2.0 * 3.14159265358979 * k / kRound;
            m.positions.emplace_back(float(r * std::cos(a)), float(r * std::sin(a)), float(z));
            m.normals.emplace_back(float(std::cos(a)), float(std::sin(a)), 0.0f);
        }
    auto id = [&](int z, int k) { return static_cast<std::uint32_t>(z * kRound + k % kRound); };
    for (int z = 0; z + 1 < kRings; ++z)
        for (int k = 0; k < kRound; ++k) {
            m.triangles.push_back({id(z, k), id(z, k + 1), id(z + 1, k + 1)});
            m.triangles.push_back({id(z, k), id(z + 1, k + 1), id(z + 1, k)});
        }
    return m;
}

TEST(Comparison, TheStripBetweenTwoFieldsOfViewIsNotAHole) {
    // The examined scan's field of view ends 8 rings before the reference's: the strip has a
    // fifth of its area in the one-edge band of the reference's rim, but half its rim on it.
    const Mesh m = tube();
    const std::size_t n = m.vertex_count();
    std::vector<std::uint8_t> seen(n, 1);
    std::vector<float> missing(n, 0.0f), distance(n, 0.0f);
    for (std::size_t v = 0; v < n; ++v)
        if (m.positions[v].z() <= 8.0f) missing[v] = 1.0f;
    const ComparisonInputs in{.seen = &seen, .missing = &missing, .distance = &distance};
    const Comparison strip = classify_comparison(m, in);
    EXPECT_EQ(strip.holes, 0u);
    EXPECT_EQ(static_cast<CompareClass>(strip.vertex_class[4 * 24]), CompareClass::NotReached);
    EXPECT_EQ(static_cast<CompareClass>(strip.vertex_class[20 * 24]), CompareClass::Compared);
    // The same area gone in the middle of the tube, on one side: the scan covered around it.
    std::fill(missing.begin(), missing.end(), 0.0f);
    for (std::size_t v = 0; v < n; ++v)
        if (std::abs(m.positions[v].z() - 20.0f) <= 4.0f && m.positions[v].x() > 0.0f)
            missing[v] = 1.0f;
    EXPECT_EQ(classify_comparison(m, in).holes, 1u);
}

TEST(Comparison, DropsADamagedStripAlongACutButKeepsADamageReachingTheCutWhole) {
    const Inputs in;
    const Mesh mesh = flat();
    const Comparison c = classify_comparison(mesh, in.view());
    std::vector<std::uint8_t> damaged(in.n, 0);
    for (int y = 5; y <= 30; ++y)
        for (int x = 0; x <= 2; ++x) damaged[vid(x, y)] = 1;  // the curl of a cut's rows
    for (int y = 0; y <= kN; ++y)
        for (int x = 0; x <= kN; ++x)
            if (std::hypot(x - 20, y - 6) <= 8.0) damaged[vid(x, y)] = 1;  // a dent at the cut
    EXPECT_EQ(drop_border_groups(mesh, damaged, c), 1u);
    EXPECT_EQ(damaged[vid(1, 20)], 0);
    EXPECT_EQ(damaged[vid(20, 0)], 1);  // the dent's border vertices stay in it
    EXPECT_EQ(damaged[vid(20, 12)], 1);
}

// A change that runs on from a thin plate (below resolution) into its surroundings is the
// plate's partial volume: a group with more than a tenth of its area there is dropped, one
// that merely touches it is kept.
TEST(Comparison, DropsAGroupRunningOnFromAThinPlateButKeepsOneThatTouchesIt) {
    Inputs in;
    const Mesh mesh = flat();
    std::vector<std::uint8_t> thin(in.n, 0);
    for (int y = 0; y <= kN; ++y)
        for (int x = 18; x <= 22; ++x) thin[vid(x, y)] = 1;  // a plate along y
    ComparisonInputs inputs = in.view();
    inputs.below_resolution = &thin;
    const Comparison c = classify_comparison(mesh, inputs);
    ASSERT_EQ(class_at(c, 20, 20), CompareClass::BelowResolution);
    std::vector<std::uint8_t> damaged(in.n, 0);
    // x 15..24 around the plate: half of the group on it.
    for (int y = 10; y <= 16; ++y)
        for (int x = 15; x <= 24; ++x) damaged[vid(x, y)] = 1;
    // x 8..22 beside it: 5 of 15 columns on the plate is a third (dropped) ...
    for (int y = 22; y <= 26; ++y)
        for (int x = 8; x <= 22; ++x) damaged[vid(x, y)] = 1;
    // ... x 5..18: 1 of 14 columns (kept whole, its thin column too).
    for (int y = 30; y <= 34; ++y)
        for (int x = 5; x <= 18; ++x) damaged[vid(x, y)] = 1;
    EXPECT_EQ(drop_border_groups(mesh, damaged, c), 2u);
    EXPECT_EQ(damaged[vid(16, 13)], 0);
    EXPECT_EQ(damaged[vid(10, 24)], 0);
    EXPECT_EQ(damaged[vid(10, 32)], 1);
    EXPECT_EQ(damaged[vid(18, 32)], 1);
    // Evidence read over a radius comes from the group's surroundings within it: a group beside
    // the plate, not on it, is kept at each vertex's own scale and dropped where that radius
    // reaches well into the plate.
    std::vector<std::uint8_t> beside(in.n, 0);
    for (int y = 12; y <= 28; ++y)
        for (int x = 12; x <= 16; ++x) beside[vid(x, y)] = 1;
    std::vector<std::uint8_t> own = beside;
    EXPECT_EQ(drop_border_groups(mesh, own, c), 0u);
    EXPECT_EQ(drop_border_groups(mesh, beside, c, 4.0), 1u);
    EXPECT_EQ(beside[vid(14, 20)], 0);
}

// decide() over the same evidence: seen everywhere, undamaged noise elsewhere.
struct Zoom {
    ZoomAtlas atlas;
    Coverage coverage;
    std::vector<float> tolerance;
    explicit Zoom(const Inputs& in) {
        atlas.value_mean.resize(in.n);
        for (std::size_t v = 0; v < in.n; ++v)
            atlas.value_mean[v] = in.missing[v] > 0.5f ? 90.0f : 0.5f + 0.5f * float(v % 3);
        atlas.value_max = atlas.value_mean;
        atlas.missing = in.missing;
        atlas.depth_mean.assign(in.n, 0.0f);
        atlas.max_view.assign(in.n, 0);
        coverage.seen = in.seen;
        coverage.fraction = 1.0;
        tolerance.assign(in.n, 0.0f);
    }
    [[nodiscard]] DecisionEvidence evidence(const Inputs& in) const {
        return {.atlas = &atlas,
                .coverage = &coverage,
                .distance = &in.distance,
                .tolerance = &tolerance,
                .at_border = &in.at_border,
                .size = 40.0 * std::sqrt(2.0)};
    }
};

TEST(Comparison, DecideCallsWornAwaySurfaceALossAndAnUnscannedPartNothing) {
    const auto cap = [](int x, int y) {
        return std::max(0.0, 2.0 - 0.25 * std::hypot(x - 20, y - 20));
    };
    Inputs worn;
    for (std::size_t v = 0; v < worn.n; ++v) worn.distance[v] = v % 2 ? 0.001f : -0.001f;
    worn.gone(20, 20, 3.0);
    const Zoom zw(worn);
    const Mesh capped = grid(cap);
    const ZoomDecision d = decide(capped, zw.evidence(worn), DecisionOptions{});
    ASSERT_EQ(d.regions.regions.size(), 1u);
    EXPECT_EQ(d.regions.regions[0].kind, RegionKind::Dent);
    EXPECT_LT(d.regions.regions[0].peak_depth, -0.5);
    EXPECT_GT(d.regions.regions[0].missing_fraction, 0.5);

    Inputs partial;
    for (std::size_t v = 0; v < partial.n; ++v) partial.distance[v] = v % 2 ? 0.001f : -0.001f;
    partial.gone(40, 20, 25.0);  // the examined scan never reached the right half
    const Zoom zp(partial);
    const ZoomDecision e = decide(flat(), zp.evidence(partial), DecisionOptions{});
    EXPECT_TRUE(e.regions.regions.empty());
    EXPECT_LT(e.comparison.fraction, 0.5);
    EXPECT_GT(e.comparison.not_reached_area, 0.0);
}

// A resection: a whole cone (height 2, radius 8: volume π·8²·2/3 = 134) and the flat round it
// out to radius 12, 28 % of the surface, are gone from an examined surface that encloses
// its solid. One loss region, listed first before a small bump elsewhere; its volume is the
// cone's solid, not its surface times its depth; the shape field holds the cone's heights there
// and nothing (NaN) where an examined part never reached.
TEST(Comparison, DecideListsSurfaceGoneFirstWithTheVolumeOfItsSolid) {
    const auto cone = [](int x, int y) {
        return std::max(0.0, 2.0 - 0.25 * std::hypot(x - 20, y - 20));
    };
    Inputs resected;
    for (std::size_t v = 0; v < resected.n; ++v) resected.distance[v] = v % 2 ? 0.001f : -0.001f;
    resected.gone(20, 20, 12.0);
    for (int y = 4; y <= 10; ++y)
        for (int x = 4; x <= 10; ++x) resected.distance[vid(x, y)] = 1.5f;  // a 7 × 7 bump
    Zoom z(resected);
    for (int y = 4; y <= 10; ++y)
        for (int x = 4; x <= 10; ++x) z.atlas.value_mean[vid(x, y)] = 40.0f;
    DecisionEvidence ev = z.evidence(resected);
    ev.examined_encloses = true;
    const Mesh mesh = grid(cone);
    const ZoomDecision d = decide(mesh, ev, DecisionOptions{});
    ASSERT_GE(d.regions.regions.size(), 2u);
    const Region& gone = d.regions.regions[0];
    EXPECT_TRUE(gone.is_hole_loss());
    EXPECT_EQ(gone.id, 1);
    EXPECT_NEAR(gone.area, std::numbers::pi * 12.0 * 12.0, 0.1 * std::numbers::pi * 144.0);
    EXPECT_NEAR(gone.volume, -std::numbers::pi * 64.0 * 2.0 / 3.0, 0.1 * 134.0);
    EXPECT_NEAR(gone.peak_depth, -2.0, 0.05);
    EXPECT_EQ(d.regions.regions[1].kind, RegionKind::Bump);
    EXPECT_LT(d.regions.regions[1].area, gone.area);
    EXPECT_FLOAT_EQ(decided_shape(resected.distance, d)[vid(20, 20)], -2.0f);

    ev.examined_encloses = false;  // the same third unscanned: nothing known there
    const ZoomDecision e = decide(mesh, ev, DecisionOptions{});
    EXPECT_TRUE(std::isnan(decided_shape(resected.distance, e)[vid(20, 20)]));
    for (const auto& r : e.regions.regions) EXPECT_FALSE(r.is_hole_loss());
}

// A thin plate or a narrow gap (analysis/resolution.h) is not compared: a shape change there
// is no region, while the same change on resolved surface is one.
TEST(Comparison, BelowResolutionIsNotComparedAndHoldsNoRegion) {
    Inputs in;
    for (std::size_t v = 0; v < in.n; ++v) in.distance[v] = v % 2 ? 0.001f : -0.001f;
    const auto bump = [&](int cx, int cy) {
        for (int y = 0; y <= kN; ++y)
            for (int x = 0; x <= kN; ++x)
                if (const double r = std::hypot(x - cx, y - cy); r <= 3.0)
                    in.distance[vid(x, y)] = static_cast<float>(1.5 * (1.0 - r / 4.0));
    };
    bump(12, 20);
    bump(28, 20);
    std::vector<std::uint8_t> thin(in.n, 0);
    for (int y = 0; y <= kN; ++y)
        for (int x = 22; x <= 34; ++x) thin[vid(x, y)] = 1;
    ComparisonInputs inputs = in.view();
    inputs.below_resolution = &thin;
    const Comparison c = classify_comparison(flat(), inputs);
    EXPECT_EQ(class_at(c, 28, 20), CompareClass::BelowResolution);
    EXPECT_EQ(class_at(c, 12, 20), CompareClass::Compared);
    EXPECT_EQ(class_at(c, 28, 2), CompareClass::ReferenceBorder);  // the border band comes first
    EXPECT_EQ(to_string(CompareClass::BelowResolution), "below resolution");
    // 13 columns of the 31 × 31 compared vertices, a unit dual area each.
    EXPECT_NEAR(c.below_resolution_area, 13.0 * 31.0, 1e-6);
    EXPECT_NEAR(c.compared_area + c.reference_border_area + c.below_resolution_area,
                c.reference_area, 1e-9);

    Zoom z(in);  // the bumps tilt the surface: strong normal evidence on them
    for (std::size_t v = 0; v < in.n; ++v)
        if (in.distance[v] > 0.1f) z.atlas.value_mean[v] = z.atlas.value_max[v] = 30.0f;
    DecisionEvidence e = z.evidence(in);
    e.below_resolution = &thin;
    const ZoomDecision d = decide(flat(), e, DecisionOptions{});
    ASSERT_EQ(d.regions.regions.size(), 1u);
    EXPECT_NEAR(d.regions.regions[0].centroid.x(), 12.0, 1.0);
    EXPECT_EQ(d.regions.regions[0].kind, RegionKind::Bump);
    // Without the flag both bumps are regions: the test would see a missed rule.
    EXPECT_EQ(decide(flat(), z.evidence(in), DecisionOptions{}).regions.regions.size(), 2u);
}

// Every vertex below the scans' resolution: nothing is compared, so the floors would be read over
// nothing. No region is reported (the bumps are strong), and no smallest damage is stated.
TEST(Comparison, NothingComparedReportsNoRegionAndStatesNoDetectableDamage) {
    Inputs in;
    for (std::size_t v = 0; v < in.n; ++v) in.distance[v] = 0.0f;
    for (int y = 0; y <= kN; ++y)
        for (int x = 0; x <= kN; ++x)
            if (std::hypot(x - 20, y - 20) <= 3.0) in.distance[vid(x, y)] = 1.5f;
    Zoom z(in);
    for (std::size_t v = 0; v < in.n; ++v)
        if (in.distance[v] > 0.1f) z.atlas.value_mean[v] = z.atlas.value_max[v] = 30.0f;
    const std::vector<std::uint8_t> all_thin(in.n, 1);
    DecisionEvidence e = z.evidence(in);
    ASSERT_EQ(decide(flat(), e, DecisionOptions{}).regions.regions.size(), 1u)
        << "compared, the bump is a region";
    e.below_resolution = &all_thin;
    const ZoomDecision d = decide(flat(), e, DecisionOptions{});
    EXPECT_EQ(d.comparison.compared_area, 0.0);
    EXPECT_TRUE(d.regions.regions.empty());
    EXPECT_EQ(d.regions.region_of_vertex, std::vector<int>(in.n, 0));
    EXPECT_TRUE(std::isnan(d.scale.min_depth));
    EXPECT_TRUE(std::isnan(d.scale.min_area));
    EXPECT_NE(d.scale.text.find("nothing of the reference was compared"), std::string::npos)
        << d.scale.text;
    EXPECT_NE(d.scale.text.find("below the scans' resolution"), std::string::npos);
    EXPECT_EQ(d.scale.text.find("smallest detectable"), std::string::npos);
    ASSERT_FALSE(d.warnings.empty());
}

}  // namespace
}  // namespace glint
