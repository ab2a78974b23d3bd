// decide() and the fused rule (decision/decision.h) on hand-made evidence over a flat grid: a
// floor from a known spread, the hysteresis reach of a region, the split of a loss from an
// adjacent gain, hole filling, and each region kind. The evidence is written vertex by vertex,
// so each expectation follows from the rule's text alone.
#include "decision/decision.h"

#include "scanner/atlas.h"
#include "scanner/coverage.h"
#include "tests/decision/flat_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace glint {
namespace {

constexpr int kN = 40;  // grid of kN × kN unit squares, (kN + 1)² vertices

Mesh grid() { return test::flat_grid(kN); }

std::size_t vid(int x, int y) { return static_cast<std::size_t>(y * (kN + 1) + x); }

/// Evidence of one zoom, every vertex seen, undamaged: a normal deviation cycling through 0.5°,
/// 1° and 1.5° (median 1, MAD 0.5, and so they stay with a few per cent of damage added) and a
/// signed distance alternating ±0.001 mm.
struct Evidence {
    Mesh mesh = grid();
    ZoomAtlas atlas;
    Coverage coverage;
    std::vector<float> distance;
    std::vector<float> tolerance;
    std::vector<std::uint8_t> at_border;

    Evidence() {
        const std::size_t n = mesh.vertex_count();
        atlas.value_mean.resize(n);
        atlas.value_max.resize(n);
        atlas.missing.assign(n, 0.0f);
        atlas.depth_mean.assign(n, 0.0f);
        atlas.max_view.assign(n, 0);
        coverage.seen.assign(n, 1);
        coverage.fraction = 1.0;
        distance.resize(n);
        tolerance.assign(n, 0.0f);
        at_border.assign(n, 0);
        for (std::size_t v = 0; v < n; ++v) {
            atlas.value_mean[v] = 0.5f + 0.5f * static_cast<float>(v % 3);
            distance[v] = v % 2 ? 0.001f : -0.001f;
        }
    }
    /// A radial change of shape at (cx, cy): distance = peak·max(0, 1 − r/radius), and a normal
    /// deviation of `normal_deg` wherever it moved.
    void change(int cx, int cy, double radius, float peak, float normal_deg) {
        for (int y = 0; y <= kN; ++y)
            for (int x = 0; x <= kN; ++x) {
                const double r = std::hypot(x - cx, y - cy);
                if (r >= radius) continue;
                distance[vid(x, y)] = peak * static_cast<float>(1.0 - r / radius);
                atlas.value_mean[vid(x, y)] = normal_deg;
            }
    }
    [[nodiscard]] DecisionEvidence view() const {
        return {.atlas = &atlas,
                .coverage = &coverage,
                .distance = &distance,
                .tolerance = &tolerance,
                .at_border = &at_border,
                .metric = Metric::AngleDeg,
                .size = std::hypot(kN, kN)};
    }
};

std::set<std::size_t> vertices_of(const ZoomDecision& d, std::int32_t id) {
    std::set<std::size_t> out;
    for (std::size_t v = 0; v < d.regions.region_of_vertex.size(); ++v)
        if (d.regions.region_of_vertex[v] == id) out.insert(v);
    return out;
}

TEST(RobustFloor, IsMedianPlusKScaledMadAndCapsWhatIsImplausible) {
    std::vector<float> values;
    for (int i = 0; i < 101; ++i) values.push_back(i % 2 ? 1.5f : 0.5f);
    values[50] = 1.0f;  // the median itself
    const std::vector<std::uint8_t> all(values.size(), 1);
    const Floor f = robust_floor(values, all, 6.0, 0.0, 100.0);
    EXPECT_DOUBLE_EQ(f.median, 1.0);
    EXPECT_DOUBLE_EQ(f.mad, 0.5);
    // note: 1.4826 makes the MAD a consistent estimate of σ for Gaussian noise.
    EXPECT_NEAR(f.value, 1.0 + 6.0 * 1.4826 * 0.5, 1e-6);
    EXPECT_FALSE(f.implausible);
    // Never below the minimum; capped (and said so) above the plausible limit.
    EXPECT_DOUBLE_EQ(robust_floor(values, all, 6.0, 9.0, 100.0).value, 9.0);
    const Floor capped = robust_floor(values, all, 6.0, 0.0, 2.0);
    EXPECT_TRUE(capped.implausible);
    EXPECT_DOUBLE_EQ(capped.value, 2.0);
    // Values not in use do not count.
    std::vector<std::uint8_t> some(values.size(), 0);
    some[0] = some[2] = some[4] = 1;  // 0.5 each
    EXPECT_DOUBLE_EQ(robust_floor(values, some, 6.0, 0.0, 100.0).value, 0.5);
}

TEST(Decide, NormalRuleFloorsAtTheMeasuredSpreadAndFillsTheRingsInside) {
    Evidence e;
    // A ring of strong deviation (radius 4..6 around (20, 20)) with a quiet inside: the
    // floor of a dent keeps its normal, so the normal field marks a ring.
    for (int y = 0; y <= kN; ++y)
        for (int x = 0; x <= kN; ++x) {
            const double r = std::hypot(x - 20, y - 20);
            if (r >= 4 && r < 6) e.atlas.value_mean[vid(x, y)] = 30.0f;
        }
    DecisionOptions o{.rule = DecisionRule::Normal};
    const ZoomDecision filled = decide(e.mesh, e.view(), o);
    EXPECT_NEAR(filled.normal.value, 1.0 + 6.0 * 1.4826 * 0.5, 1e-3);  // the ring is a minority
    ASSERT_EQ(filled.regions.regions.size(), 1u);
    EXPECT_GT(filled.regions.filled_vertices, 0u);
    EXPECT_EQ(filled.regions.region_of_vertex[vid(20, 20)], 1) << "the inside is filled";
    o.fill_holes = false;
    const ZoomDecision ring = decide(e.mesh, e.view(), o);
    ASSERT_EQ(ring.regions.regions.size(), 1u);
    EXPECT_EQ(ring.regions.filled_vertices, 0u);
    EXPECT_EQ(ring.regions.region_of_vertex[vid(20, 20)], 0) << "the inside stays out";
    EXPECT_LT(ring.regions.regions[0].vertex_count, filled.regions.regions[0].vertex_count);
}

TEST(Decide, FusedRuleGrowsARegionToATenthOfItsPeak) {
    Evidence e;
    e.change(20, 20, 8.0, -1.0f, 10.0f);  // a cone-shaped dent, 1 mm deep, radius 8
    const ZoomDecision d = decide(e.mesh, e.view(), DecisionOptions{});
    ASSERT_EQ(d.regions.regions.size(), 1u) << d.rule_text;
    const Region& r = d.regions.regions[0];
    EXPECT_EQ(r.kind, RegionKind::Dent);
    EXPECT_NEAR(r.peak_depth, -1.0, 1e-6);
    // Hysteresis: the extent holds exactly the connected vertices whose distance reaches
    // grow_fraction (0.1) of the peak, i.e. r ≤ 7.2 — far beyond the strong core that reaches
    // the shape floor (a few hundredths of a mm here).
    const std::set<std::size_t> got = vertices_of(d, 1);
    std::set<std::size_t> want;
    for (int y = 0; y <= kN; ++y)
        for (int x = 0; x <= kN; ++x)
            if (std::hypot(x - 20, y - 20) <= 8.0 * 0.9 + 1e-9) want.insert(vid(x, y));
    EXPECT_EQ(got, want);
    EXPECT_FALSE(r.evidence.empty());
}

TEST(Decide, FusedRuleSplitsALossFromAnAdjacentGain) {
    Evidence e;
    e.change(14, 20, 6.0, -0.8f, 8.0f);
    e.change(26, 20, 6.0, +0.6f, 8.0f);  // the two cones touch at x = 20
    const ZoomDecision d = decide(e.mesh, e.view(), DecisionOptions{});
    ASSERT_EQ(d.regions.regions.size(), 2u);
    int dents = 0, bumps = 0;
    for (const Region& r : d.regions.regions) {
        dents += r.kind == RegionKind::Dent;
        bumps += r.kind == RegionKind::Bump;
        if (r.kind == RegionKind::Dent) {
            EXPECT_LT(r.centroid.x(), 20.0);
        }
        if (r.kind == RegionKind::Bump) {
            EXPECT_GT(r.centroid.x(), 20.0);
        }
    }
    EXPECT_EQ(dents, 1);
    EXPECT_EQ(bumps, 1);
}

TEST(Decide, FusedRuleNeedsTheNormalFieldToCorroborateAShapeChange) {
    Evidence e;
    e.change(20, 20, 8.0, -1.0f, 1.0f);  // moved, but the normals did not turn beyond the noise
    const ZoomDecision d = decide(e.mesh, e.view(), DecisionOptions{});
    EXPECT_TRUE(d.regions.regions.empty());
}

// A patch without examined surface inside covered surface is a hole (decision/comparison.h).
// On a flat part of a one-view scan its rim cannot tell removed material from a scanner's
// dropout: "missing surface". An examined surface that is no one-view scan cannot drop out:
// the same hole is material gone, a dent whose depth (nothing stood above the flat rim: 0) is
// a lower bound. A worn cap is a loss on either: comparison_test.cpp.
TEST(Decide, AHoleOverAFlatPartIsALossUnlessTheExaminedSurfaceIsAOneViewScan) {
    Evidence e;
    for (int y = 10; y <= 14; ++y)
        for (int x = 10; x <= 14; ++x) {
            e.atlas.missing[vid(x, y)] = 1.0f;
            e.atlas.value_mean[vid(x, y)] = 90.0f;  // the metric's missing value
        }
    const ZoomDecision d = decide(e.mesh, e.view(), DecisionOptions{});
    ASSERT_EQ(d.regions.regions.size(), 1u);
    EXPECT_EQ(d.regions.regions[0].kind, RegionKind::Dent);
    EXPECT_EQ(d.regions.regions[0].peak_depth, 0.0);
    EXPECT_TRUE(d.regions.regions[0].hole);
    EXPECT_GT(d.regions.regions[0].missing_fraction, 0.5);
    EXPECT_NE(d.regions.regions[0].evidence.find("surface gone"), std::string::npos);
    EXPECT_EQ(d.comparison.holes, 1u);
    EXPECT_EQ(d.comparison.lost_holes, 1u);
    EXPECT_EQ(vertices_of(d, 1).size(), 25u);

    const ScanView facing{.direction = Vec3d(0.0, 0.0, 1.0), .cone_deg = 77.0};
    DecisionEvidence one_view = e.view();
    one_view.scan_view = &facing;
    const ZoomDecision s = decide(e.mesh, one_view, DecisionOptions{});
    ASSERT_EQ(s.regions.regions.size(), 1u);
    EXPECT_EQ(s.regions.regions[0].kind, RegionKind::MissingSurface);
    EXPECT_EQ(s.comparison.holes, 1u);
    EXPECT_EQ(s.comparison.lost_holes, 0u);
    EXPECT_EQ(vertices_of(s, 1).size(), 25u);
}

TEST(Decide, GivenThresholdsAreUsedAsGivenAndUnmeasurableFloorsAreWarnedAbout) {
    Evidence e;
    DecisionOptions o{.threshold = 7.5, .shape_threshold = 0.2};
    const ZoomDecision given = decide(e.mesh, e.view(), o);
    EXPECT_TRUE(given.normal.given);
    EXPECT_DOUBLE_EQ(given.normal.value, 7.5);
    EXPECT_TRUE(given.shape.given);
    EXPECT_DOUBLE_EQ(given.shape.low, 0.1);
    EXPECT_EQ(given.normal.source, FloorSource::Given);
    EXPECT_EQ(given.shape.source, FloorSource::Given);
    // Half the surface turned by 40°: under the normal rule the estimated floor is implausible,
    // capped and reported.
    for (std::size_t v = 0; v < e.atlas.value_mean.size(); v += 2) e.atlas.value_mean[v] = 40.0f;
    const ZoomDecision capped =
        decide(e.mesh, e.view(), DecisionOptions{.rule = DecisionRule::Normal});
    EXPECT_TRUE(capped.normal.implausible);
    EXPECT_EQ(capped.normal.source, FloorSource::Capped);
    EXPECT_DOUBLE_EQ(capped.normal.value, 20.0);
    ASSERT_FALSE(capped.warnings.empty());
    EXPECT_NE(capped.warnings[0].find("normal evidence floor"), std::string::npos);
}

TEST(Decide, FloorsSayHowTheyWereObtained) {
    Evidence e;
    const ZoomDecision d = decide(e.mesh, e.view(), DecisionOptions{});
    // Normal: 1 + 6·1.4826·0.5 ≈ 5.4° is measured; shape: ±0.001 on a 56.6 size is below
    // 1e-5 × size only when the spread is; here it is measured as well.
    EXPECT_EQ(d.normal.source, FloorSource::Measured);
    for (auto& v : e.atlas.value_mean) v = 0.01f;
    const ZoomDecision low = decide(e.mesh, e.view(), DecisionOptions{});
    EXPECT_EQ(low.normal.source, FloorSource::Minimum);
    EXPECT_DOUBLE_EQ(low.normal.value, 2.0);
    EXPECT_LT(low.normal.estimate, 2.0);
    EXPECT_EQ(to_string(FloorSource::Capped), "capped");
}

// Every number followed by ° in a sentence: at most 180.
double largest_angle_in(const std::string& text) {
    double largest = 0.0;
    for (std::size_t at = text.find("°"); at != std::string::npos; at = text.find("°", at + 1)) {
        std::size_t b = at;
        while (b > 0 &&
               (std::isdigit(static_cast<unsigned char>(text[b - 1])) || text[b - 1] == '.'))
            --b;
        if (b < at) largest = std::max(largest, std::stod(text.substr(b, at - b)));
    }
    return largest;
}

TEST(Decide, NoAngleAbove180IsStated) {
    Evidence e;
    // Most of the surface unlike: angles between 30° and 150° (median 90°, MAD 30°: the
    // estimate median + 6·1.4826·MAD ≈ 357° is no angle).
    for (std::size_t v = 0; v < e.atlas.value_mean.size(); ++v)
        e.atlas.value_mean[v] = 30.0f + 30.0f * static_cast<float>(v % 5);
    const ZoomDecision d = decide(e.mesh, e.view(), DecisionOptions{.rule = DecisionRule::Normal});
    ASSERT_TRUE(d.normal.implausible);
    EXPECT_GT(d.normal.estimate, 180.0);
    EXPECT_LE(d.normal.value, 180.0);
    for (const auto& w : d.warnings) EXPECT_LE(largest_angle_in(w), 180.0) << w;
    EXPECT_NE(d.normal.note.find("beyond 180°"), std::string::npos) << d.normal.note;
}

TEST(Decide, ImplausibleFloorsMoveToTheScaleWhereTheMajorityIsQuiet) {
    // Rough evidence everywhere: the distance uniform in ±0.3 (its floor far beyond 1 % of the
    // size) and the normals anywhere between 1° and 40°; a 3-deep loss of radius 9 is added below.
    Evidence e;
    std::uint32_t state = 12345;
    auto uniform = [&state] {  // in [0, 1): a fixed linear congruential sequence
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / static_cast<float>(1u << 24);
    };
    for (std::size_t v = 0; v < e.distance.size(); ++v) {
        e.distance[v] = 0.6f * (uniform() - 0.5f);
        e.atlas.value_mean[v] = 1.0f + 39.0f * uniform();
    }
    const ZoomDecision quiet = decide(e.mesh, e.view(), DecisionOptions{});
    EXPECT_TRUE(quiet.scale.searched);
    EXPECT_TRUE(quiet.scale.quiet);
    EXPECT_GT(quiet.scale.radius, 0.0);
    EXPECT_TRUE(quiet.scale.own_shape.implausible);
    EXPECT_FALSE(quiet.shape.implausible);
    EXPECT_FALSE(quiet.normal.implausible);
    EXPECT_GT(quiet.scale.min_depth, 0.0);
    // One resolution element: the disc where the fit's Gaussian weights (σ = r/2) stand above
    // half their peak, radius 0.589·r.
    const double half = 0.5 * quiet.scale.radius * std::sqrt(2.0 * std::log(2.0));
    EXPECT_NEAR(quiet.scale.min_area, 3.14159265 * half * half, 1e-3);
    EXPECT_TRUE(quiet.regions.regions.empty());
    ASSERT_FALSE(quiet.warnings.empty());
    EXPECT_NE(quiet.warnings[0].find("read over a radius of"), std::string::npos);

    for (int y = 0; y <= kN; ++y)
        for (int x = 0; x <= kN; ++x) {
            const double r = std::hypot(x - 20, y - 20);
            if (r < 9) e.distance[vid(x, y)] += static_cast<float>(-3.0 * (1 - r / 9));
        }
    const ZoomDecision dent = decide(e.mesh, e.view(), DecisionOptions{});
    EXPECT_TRUE(dent.scale.quiet);
    ASSERT_EQ(dent.regions.regions.size(), 1u);
    EXPECT_EQ(dent.regions.regions[0].kind, RegionKind::Dent);
    EXPECT_NEAR(dent.regions.regions[0].centroid.x(), 20.0, 1.5);
    EXPECT_NEAR(dent.regions.regions[0].centroid.y(), 20.0, 1.5);
}

TEST(Decide, AKnownVoxelReadsTheEvidenceNoFinerThanAVoxel) {
    // Quiet evidence (plausible floors at each vertex's own scale) with a 3-deep loss of radius
    // 9; the scans' voxel is 3 units. The grid's median edge is √2 (half its triangles' first
    // edges are diagonals) and, stated 200 units large, the ladder is 2, 4 and 8 edges: 4√2 is
    // the first rung no finer than a voxel. Reading there is how scans are read, not a warning.
    // Two scans differ everywhere by their sampling: here ±0.1 (3 % of the voxel).
    Evidence e;
    for (std::size_t v = 0; v < e.distance.size(); ++v) e.distance[v] = v % 2 ? 0.1f : -0.1f;
    e.change(20, 20, 9.0, -3.0f, 30.0f);
    DecisionEvidence view = e.view();
    view.size = 200.0;
    view.voxel = 3.0;
    const ZoomDecision d = decide(e.mesh, view, DecisionOptions{});
    EXPECT_TRUE(d.scale.searched);
    EXPECT_TRUE(d.scale.quiet);
    EXPECT_NEAR(d.scale.radius, 4.0 * std::sqrt(2.0), 1e-5);
    EXPECT_EQ(d.scale.tried.size(), 1u) << "no rung finer than the voxel is tried";
    EXPECT_FALSE(d.scale.own_normal.implausible);
    EXPECT_NE(d.scale.text.find("no finer than a voxel"), std::string::npos) << d.scale.text;
    EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();
    ASSERT_EQ(d.regions.regions.size(), 1u);
    EXPECT_EQ(d.regions.regions[0].kind, RegionKind::Dent);
    EXPECT_NEAR(d.regions.regions[0].centroid.x(), 20.0, 1.5);
    // Without a voxel the same evidence is read at each vertex's own scale.
    view.voxel = 0.0;
    const ZoomDecision own = decide(e.mesh, view, DecisionOptions{});
    EXPECT_FALSE(own.scale.searched);
    EXPECT_EQ(own.scale.radius, 0.0);
    ASSERT_EQ(own.regions.regions.size(), 1u);
    // A surface derived from the reference (a mesh edit of it: it coincides with the reference
    // on the undamaged majority) was not sampled apart from it; nothing below a voxel to read
    // past, so its own scale stands, voxel or not.
    std::vector<float> coincident = e.distance;
    for (auto& x : coincident)
        if (std::abs(x) == 0.1f) x = 0.0f;  // the ±0.1 sampling off, the loss kept
    view.voxel = 3.0;
    view.distance = &coincident;
    const ZoomDecision same = decide(e.mesh, view, DecisionOptions{});
    EXPECT_FALSE(same.scale.searched);
    ASSERT_EQ(same.regions.regions.size(), 1u);
    EXPECT_EQ(same.regions.regions[0].kind, RegionKind::Dent);
}

// A change the statement says the run can tell, left without a region, is warned about with
// where it lies and why (issue 50): here the normals never turned, so nothing corroborates it.
TEST(Decide, AChangeBeyondTheStatedLimitWithoutARegionIsWarnedAboutWithItsPlace) {
    // 0.2 deep over a radius of 9: the surface tilts by 1.3°, under the normal floor's 2°.
    Evidence e;
    e.change(20, 20, 9.0, -0.2f, 1.0f);
    DecisionEvidence view = e.view();
    view.size = 200.0;
    // the scans' sampling (±0.001) 1.5 % of the voxel: read no finer than it
    view.voxel = 0.1;
    view.unit = "mm";
    const ZoomDecision d = decide(e.mesh, view, DecisionOptions{});
    EXPECT_TRUE(d.regions.regions.empty());
    ASSERT_EQ(d.warnings.size(), 1u);
    const std::string& w = d.warnings[0];
    EXPECT_NE(w.find("1 place(s) where the shape change reaches"), std::string::npos) << w;
    EXPECT_NE(w.find("around (20.0, 20.0, 0.0) mm"), std::string::npos) << w;
    EXPECT_NE(w.find("does not corroborate"), std::string::npos) << w;
    // Corroborated, the same change is a region and nothing is left to warn about.
    Evidence turned;
    turned.change(20, 20, 9.0, -3.0f, 30.0f);
    view.atlas = &turned.atlas;
    view.distance = &turned.distance;
    const ZoomDecision found = decide(turned.mesh, view, DecisionOptions{});
    EXPECT_EQ(found.regions.regions.size(), 1u);
    EXPECT_TRUE(found.warnings.empty()) << found.warnings.front();
}

// Faces across thick slices stand on wider terraces (DecisionEvidence::sampling): the spread
// of the distance is measured per band of the grid's staircase step along the normal, and a
// change is judged against surface sampled as it was. Two equal bumps (4 high), one where the grid is 1
// unit wide along the normal and the surface's terraces differ by ±0.05, one where it is 2
// units wide and they differ by ±0.5: only the first stands out from its own band.
TEST(Decide, TheDistanceIsJudgedPerBandOfTheGridsWidthAlongTheNormal) {
    constexpr int n = 80;
    test::FlatEvidence g(n);
    const Mesh& m = g.mesh;
    auto id = [](int x, int y) { return test::grid_vertex(n, x, y); };
    std::vector<float>& distance = g.distance;
    std::vector<float> sampling(m.vertex_count());
    std::uint32_t state = 777;
    auto uniform = [&state] {  // in [-0.5, 0.5)
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / static_cast<float>(1u << 24) - 0.5f;
    };
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) {
            const bool across = x >= n / 2;
            sampling[id(x, y)] = across ? 2.0f : 1.0f;
            // terraces: plateaus 16 rows wide, ±0.5 where the grid is thick along the normal,
            // ±0.05 where it is thin, with a speck of noise
            const float terrace = (y / 16) % 2 ? 1.0f : -1.0f;
            distance[id(x, y)] = (across ? 0.5f : 0.05f) * terrace + 0.01f * uniform();
        }
    for (const int cx : {20, 60})
        for (int y = 0; y <= n; ++y)
            for (int x = 0; x <= n; ++x) {
                const double r = std::hypot(x - cx, y - 54);
                if (r < 10) distance[id(x, y)] += static_cast<float>(4.0 * (1 - r / 10));
            }
    DecisionEvidence view = g.view(3.0, 400.0);
    view.sampling = &sampling;
    const ZoomDecision d = decide(m, view, DecisionOptions{});
    ASSERT_EQ(d.scale.sampling_bands.size(), 2u) << "two widths: two bands";
    EXPECT_GT(d.scale.min_depth_across, 3.0 * d.scale.min_depth);
    EXPECT_NE(d.scale.text.find("where faces lie across"), std::string::npos) << d.scale.text;
    ASSERT_EQ(d.regions.regions.size(), 1u);
    EXPECT_NEAR(d.regions.regions[0].centroid.x(), 20.0, 2.0);
    EXPECT_NEAR(d.regions.regions[0].centroid.y(), 54.0, 2.0);
    // It stands far out from the undamaged surface (its 4-unit peak against a quiet band of
    // ±0.05 terraces): beyond the floor's k spreads, and no place of the undamaged surface
    // stands as high, so the family-wise p is the Gaussian bound over the elements searched.
    const Region& bump = d.regions.regions[0];
    EXPECT_GE(bump.z, DecisionOptions{}.shape_k);
    EXPECT_GT(d.scale.resels, 10.0);
    EXPECT_LT(bump.p_value, 1e-6);
    // A z this far out underflows erfc; a p is never stated as 0.
    EXPECT_GT(bump.p_value, 0.0) << "z " << bump.z;
    // The detection limit as a curve: the scale read first, then each wider rung of the
    // ladder up to its largest, areas growing, no depth below the data's resolution.
    ASSERT_GE(d.scale.limit_curve.size(), 2u);
    EXPECT_DOUBLE_EQ(d.scale.limit_curve[0].radius, d.scale.radius);
    EXPECT_DOUBLE_EQ(d.scale.limit_curve[0].depth, d.scale.min_depth);
    EXPECT_DOUBLE_EQ(d.scale.limit_curve[0].area, d.scale.min_area);
    for (std::size_t k = 1; k < d.scale.limit_curve.size(); ++k) {
        EXPECT_GT(d.scale.limit_curve[k].area, d.scale.limit_curve[k - 1].area);
        EXPECT_GE(d.scale.limit_curve[k].depth, d.scale.resolution_depth);
        EXPECT_GE(d.scale.limit_curve[k].depth_across, d.scale.limit_curve[k].depth);
    }
    // The terminal's line names the wider scales: shallower depths there, or none shallower
    // (here the data's resolution, half the median edge, bounds every rung).
    EXPECT_NE(d.scale.text.find("wider"), std::string::npos) << d.scale.text;
    // Without the widths, one floor over both halves: the bump on the loud half's raised terrace
    // stands out from it as well.
    view.sampling = nullptr;
    const ZoomDecision one = decide(m, view, DecisionOptions{});
    EXPECT_TRUE(one.scale.sampling_bands.empty());
    EXPECT_EQ(one.regions.regions.size(), 2u);
}

// Two copies of one tessellation differ by a thousandth of an edge: the floor measured there
// is no depth the data could resolve. The stated limit is never below half the median edge.
TEST(Decide, TheSmallestDetectableDepthIsNeverBelowTheDatasResolution) {
    Evidence e;  // distance ±0.001 on a grid of unit and diagonal edges
    const ZoomDecision d = decide(e.mesh, e.view(), DecisionOptions{});
    EXPECT_GE(d.scale.resolution_depth, 0.5);
    EXPECT_LE(d.scale.resolution_depth, 0.5 * std::sqrt(2.0) + 1e-6);
    EXPECT_LT(d.shape.value, 0.1 * d.scale.resolution_depth) << "the floor itself stays measured";
    EXPECT_DOUBLE_EQ(d.scale.min_depth, d.scale.resolution_depth);
    EXPECT_NE(d.scale.text.find("the data's resolution"), std::string::npos) << d.scale.text;
}

TEST(Decide, WhereNoScaleQuietsTheMajorityNoRegionIsReported) {
    // Waves 1.5 deep and 24 long over the whole grid: coherent at every scale tried (at most
    // 8 % of the size), so no floor becomes plausible.
    Evidence e;
    for (int y = 0; y <= kN; ++y)
        for (int x = 0; x <= kN; ++x) {
            e.distance[vid(x, y)] = static_cast<float>(1.5 * std::sin(x * 2 * 3.14159 / 24) *
                                                       std::cos(y * 2 * 3.14159 / 24));
            e.atlas.value_mean[vid(x, y)] = 5.0f + 30.0f * static_cast<float>((x + y) % 3);
        }
    const ZoomDecision d = decide(e.mesh, e.view(), DecisionOptions{});
    EXPECT_TRUE(d.scale.searched);
    EXPECT_FALSE(d.scale.quiet);
    EXPECT_FALSE(d.scale.tried.empty());
    EXPECT_TRUE(d.regions.regions.empty());
    ASSERT_FALSE(d.warnings.empty());
    EXPECT_NE(d.warnings.back().find("no regions are reported"), std::string::npos);
}

// One surface against its mirror image (DecisionOptions::natural_floors): nothing is capped,
// and where the normals differ beyond the plausible limit by nature they neither corroborate
// nor mark missing surface; the shape decides alone, against its measured floor.
TEST(Decide, NaturalFloorsDecideOnShapeAloneWhereTheNormalsDifferByNature) {
    Evidence e;
    for (int y = 0; y <= kN; ++y)
        for (int x = 0; x <= kN; ++x)  // median 35°, MAD 30°: beyond 20° by nature
            e.atlas.value_mean[vid(x, y)] = 5.0f + 30.0f * static_cast<float>((x + y) % 3);
    e.change(20, 20, 6.0, -1.0f, 5.0f);  // a loss whose normals turned less than the nature
    for (int y = 30; y <= 33; ++y)
        for (int x = 4; x <= 7; ++x) {  // the mirror has no surface here (its own hole)
            e.atlas.missing[vid(x, y)] = 1.0f;
            e.atlas.value_mean[vid(x, y)] = 90.0f;
        }
    DecisionOptions natural;
    natural.natural_floors = true;
    const ZoomDecision d = decide(e.mesh, e.view(), natural);
    EXPECT_FALSE(d.normal.implausible);
    EXPECT_FALSE(d.shape.implausible);
    EXPECT_FALSE(d.normal.corroborates);
    EXPECT_FALSE(d.scale.searched);  // nothing implausible, no voxel: each vertex's own scale
    ASSERT_EQ(d.regions.regions.size(), 1u);
    EXPECT_EQ(d.regions.regions[0].kind, RegionKind::Dent);
    EXPECT_TRUE(vertices_of(d, d.regions.regions[0].id).contains(vid(20, 20)));
    EXPECT_EQ(d.regions.region_of_vertex[vid(5, 31)], 0);  // the mirror's hole: no finding
    EXPECT_TRUE(d.rule_text.starts_with("fused, shape alone")) << d.rule_text;
    ASSERT_FALSE(d.warnings.empty());
    EXPECT_NE(d.warnings.back().find("the shape decides alone"), std::string::npos)
        << d.warnings.back();

    // The same evidence as a pair of scans: the normal floor is implausible (capped), and the
    // missing patch, normal evidence beyond it, is missing surface.
    const ZoomDecision pair = decide(e.mesh, e.view(), DecisionOptions{});
    EXPECT_TRUE(pair.normal.implausible || pair.scale.searched);
    EXPECT_TRUE(pair.normal.corroborates);

    // Where the normals are quiet by nature they still corroborate: a shape change whose
    // normals did not turn is no region (as FusedRuleNeedsTheNormalFieldToCorroborate…).
    Evidence quiet;
    quiet.change(20, 20, 8.0, -1.0f, 1.0f);
    const ZoomDecision q = decide(quiet.mesh, quiet.view(), natural);
    EXPECT_TRUE(q.normal.corroborates);
    EXPECT_TRUE(q.regions.regions.empty());
}

TEST(Decide, WithoutShapeEvidenceTheFusedRuleFallsBackToTheNormalRuleAndSaysSo) {
    Evidence e;
    DecisionEvidence view = e.view();
    view.distance = nullptr;
    const ZoomDecision d = decide(e.mesh, view, DecisionOptions{});
    EXPECT_EQ(d.rule, DecisionRule::Normal);
    ASSERT_FALSE(d.warnings.empty());
    EXPECT_NE(d.warnings[0].find("normal rule decided alone"), std::string::npos);
}

// What a picture paints: the signed distance outside holes; in a hole the depth of the surface
// gone where it is a loss or reaches the shape floor, 0 where no loss is measurable.
TEST(DecidedShape, PaintsAHoleWithTheDepthGoneNotTheDistanceToItsRim) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    ZoomDecision d;
    d.rule = DecisionRule::Fused;
    d.shape.value = 0.1;
    // vertex 0 outside holes; 1 a loss hole shallower than the floor; 2 a hole deeper than
    // the floor; 3 a shallow hole that is no loss (a one-view scan's flat patch).
    d.comparison.in_hole = {0, 1, 1, 1};
    d.comparison.hole_depth = {nan, -0.02f, -0.3f, -0.05f};
    d.comparison.hole_loss = {0, 1, 0, 0};
    const std::vector<float> distance = {0.04f, 0.37f, 0.2f, 0.3f};
    const std::vector<float> shape = decided_shape(distance, d);
    ASSERT_EQ(shape.size(), 4u);
    EXPECT_FLOAT_EQ(shape[0], 0.04f);   // outside: the signed distance
    EXPECT_FLOAT_EQ(shape[1], -0.02f);  // a loss: its depth, a lower bound
    EXPECT_FLOAT_EQ(shape[2], -0.3f);   // beyond the floor
    EXPECT_FLOAT_EQ(shape[3], 0.0f);    // no measurable loss
    // The normal rule has no shape floor: every hole's depth shows.
    d.rule = DecisionRule::Normal;
    EXPECT_FLOAT_EQ(decided_shape(distance, d)[3], -0.05f);
    // No comparison (no holes known): the distance as it is.
    d.comparison = Comparison{};
    EXPECT_EQ(decided_shape(distance, d), distance);
}

}  // namespace
}  // namespace glint
