#include "decision/regions.h"
#include "decision/decision.h"
#include "scanner/atlas.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// A flat n×n grid of unit squares in the xy plane.
Mesh grid(int n) {
    Mesh m;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) m.positions.emplace_back(float(x), float(y), 0.f);
    auto id = [n](int x, int y) { return static_cast<std::uint32_t>(y * (n + 1) + x); };
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            m.triangles.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1)});
            m.triangles.push_back({id(x, y), id(x + 1, y + 1), id(x, y + 1)});
        }
    return m;
}

std::vector<std::uint8_t> at_least(const std::vector<float>& value, float threshold) {
    std::vector<std::uint8_t> m(value.size());
    for (std::size_t v = 0; v < value.size(); ++v) m[v] = value[v] >= threshold;
    return m;
}

TEST(FindRegions, GroupsConnectedDamageAndMeasuresIt) {
    const int n = 20;
    const Mesh m = grid(n);
    const std::size_t nv = m.vertex_count();
    std::vector<float> angle(nv, 0.5f), distance(nv, 0.0f);
    std::vector<std::uint8_t> seen(nv, 1);
    std::vector<std::int32_t> view(nv, 0);
    auto id = [n](int x, int y) { return static_cast<std::size_t>(y * (n + 1) + x); };
    // A 3×3 dent at (3..5, 3..5) and a 2×2 bump at (15..16, 15..16); one lone vertex.
    for (int y = 3; y <= 5; ++y)
        for (int x = 3; x <= 5; ++x) {
            angle[id(x, y)] = 10.f;
            distance[id(x, y)] = -0.2f;
            view[id(x, y)] = 7;
        }
    angle[id(4, 4)] = 12.f;
    for (int y = 15; y <= 16; ++y)
        for (int x = 15; x <= 16; ++x) {
            angle[id(x, y)] = 6.f;
            distance[id(x, y)] = 0.1f;
        }
    angle[id(10, 10)] = 9.f;
    const RegionResult r = find_regions(m, at_least(angle, 5.f), seen,
                                        {.value = &angle, .shape = &distance, .view = &view},
                                        RegionOptions{.min_vertices = 3});
    ASSERT_EQ(r.regions.size(), 2u);
    EXPECT_EQ(r.dropped_small, 1u);
    EXPECT_EQ(r.damaged_vertices, 9u + 4u + 1u);
    const Region& dent = r.regions[0];
    EXPECT_EQ(dent.id, 1);
    EXPECT_EQ(dent.vertex_count, 9u);
    EXPECT_EQ(dent.kind, RegionKind::Dent);
    EXPECT_NEAR(dent.centroid.x(), 4.0, 1e-9);
    EXPECT_NEAR(dent.centroid.y(), 4.0, 1e-9);
    EXPECT_DOUBLE_EQ(dent.max_value, 12.0);
    EXPECT_EQ(dent.best_view, 7);
    EXPECT_NEAR(dent.peak_depth, -0.2, 1e-6);
    EXPECT_NEAR(dent.mean_depth, -0.2, 1e-6);
    EXPECT_NEAR(dent.volume, -0.2 * 9.0, 1e-5);
    // Interior grid vertices carry one unit of area each (dual area of 6 half-squares / 3).
    EXPECT_NEAR(dent.area, 9.0, 1e-9);
    EXPECT_EQ(r.regions[1].kind, RegionKind::Bump);
    EXPECT_EQ(r.region_of_vertex[id(4, 4)], 1);
    EXPECT_EQ(r.region_of_vertex[id(10, 10)], 0);
}

TEST(FindRegions, OnlyComparedAreaMeetsTheSmallestDetectableArea) {
    // Two 3×3 groups (9 units of area each) against a smallest detectable area of 8: the one
    // with two of its vertices not compared (below resolution) holds 7 compared units and is
    // not a region; the other is, and keeps its whole area.
    const int n = 20;
    const Mesh m = grid(n);
    const std::size_t nv = m.vertex_count();
    std::vector<float> angle(nv, 0.5f);
    const std::vector<std::uint8_t> seen(nv, 1);
    std::vector<std::uint8_t> counted(nv, 1);
    auto id = [n](int x, int y) { return static_cast<std::size_t>(y * (n + 1) + x); };
    for (int y = 3; y <= 5; ++y)
        for (int x = 3; x <= 5; ++x) {
            angle[id(x, y)] = 10.f;
            angle[id(x + 10, y + 10)] = 10.f;
        }
    counted[id(13, 13)] = counted[id(14, 13)] = 0;
    RegionOptions o{.min_vertices = 3, .min_area = 8.0};
    o.min_area_counted = &counted;
    const RegionResult r = find_regions(m, at_least(angle, 5.f), seen, {.value = &angle}, o);
    ASSERT_EQ(r.regions.size(), 1u);
    EXPECT_EQ(r.dropped_small, 1u);
    EXPECT_NEAR(r.regions[0].centroid.x(), 4.0, 1e-9);
    EXPECT_NEAR(r.regions[0].area, 9.0, 1e-9);
    // Without the mask every vertex counts: both are regions.
    o.min_area_counted = nullptr;
    EXPECT_EQ(find_regions(m, at_least(angle, 5.f), seen, {.value = &angle}, o).regions.size(), 2u);
}

// A group shallower than the run can tell at its peak is no region (RegionOptions::min_depth):
// two equal 3×3 groups, one 0.4 deep, one 1.0 deep, against a limit of 0.5 everywhere but at
// the deep group's peak, where the grid's staircase makes it 1.2 (half a step of 2.4): only
// the shallow one is dropped where the limit is 0.5, and both where the step is coarse.
TEST(FindRegions, AGroupShallowerThanTheLimitAtItsPeakIsDropped) {
    const int n = 20;
    const Mesh m = grid(n);
    const std::size_t nv = m.vertex_count();
    std::vector<float> angle(nv, 0.5f), shape(nv, 0.0f), limit(nv, 0.5f);
    const std::vector<std::uint8_t> seen(nv, 1);
    auto id = [n](int x, int y) { return static_cast<std::size_t>(y * (n + 1) + x); };
    for (int y = 3; y <= 5; ++y)
        for (int x = 3; x <= 5; ++x) {
            angle[id(x, y)] = angle[id(x + 10, y + 10)] = 10.f;
            shape[id(x, y)] = -0.3f;
            shape[id(x + 10, y + 10)] = -0.8f;
        }
    shape[id(4, 4)] = -0.4f;
    shape[id(14, 14)] = -1.0f;
    RegionOptions o{.min_vertices = 3};
    o.min_depth = &limit;
    const RegionFields f{.value = &angle, .shape = &shape};
    RegionResult r = find_regions(m, at_least(angle, 5.f), seen, f, o);
    ASSERT_EQ(r.regions.size(), 1u);
    EXPECT_EQ(r.dropped_shallow, 1u);
    EXPECT_NEAR(r.regions[0].peak_depth, -1.0, 1e-6);
    limit[id(14, 14)] = 1.2f;
    r = find_regions(m, at_least(angle, 5.f), seen, f, o);
    EXPECT_TRUE(r.regions.empty());
    EXPECT_EQ(r.dropped_shallow, 2u);
    // Without a limit both are regions.
    o.min_depth = nullptr;
    EXPECT_EQ(find_regions(m, at_least(angle, 5.f), seen, f, o).regions.size(), 2u);
}

TEST(FindRegions, FillsTheFloorOfARingShapedDent) {
    // The angle marks a dent's flanks, not its floor: a ring. Its inside belongs to it.
    const int n = 20;
    const Mesh m = grid(n);
    std::vector<float> angle(m.vertex_count(), 0.f);
    std::vector<std::uint8_t> seen(m.vertex_count(), 1);
    auto id = [n](int x, int y) { return static_cast<std::size_t>(y * (n + 1) + x); };
    for (int y = 5; y <= 11; ++y)
        for (int x = 5; x <= 11; ++x)
            if (std::max(std::abs(x - 8), std::abs(y - 8)) >= 2)
                angle[id(x, y)] = 10.f;  // ring, hole 3×3
    const RegionFields fields{.value = &angle};
    const RegionResult filled = find_regions(m, at_least(angle, 5.f), seen, fields);
    ASSERT_EQ(filled.regions.size(), 1u);
    EXPECT_EQ(filled.filled_vertices, 9u);
    EXPECT_EQ(filled.regions[0].vertex_count, 49u);
    EXPECT_EQ(filled.region_of_vertex[id(8, 8)], 1);
    const RegionResult ring =
        find_regions(m, at_least(angle, 5.f), seen, fields, RegionOptions{.fill_holes = false});
    EXPECT_EQ(ring.regions[0].vertex_count, 40u);
    // An unseen vertex in the hole keeps it open: unseen is never declared damaged.
    seen[id(8, 8)] = 0;
    EXPECT_EQ(find_regions(m, at_least(angle, 5.f), seen, fields).filled_vertices, 0u);
}

TEST(FindRegions, UnseenVerticesAreNeverDamaged) {
    const Mesh m = grid(4);
    std::vector<float> angle(m.vertex_count(), 50.f);
    std::vector<std::uint8_t> seen(m.vertex_count(), 0);
    const RegionResult r = find_regions(m, at_least(angle, 5.f), seen, {.value = &angle});
    EXPECT_TRUE(r.regions.empty());
    EXPECT_EQ(r.damaged_vertices, 0u);
}

TEST(AtlasAccumulator, KeepsMaxMeanCountAndMostFrontalView) {
    const Mesh m = grid(1);  // two triangles, four vertices
    AtlasAccumulator acc(m, 0.1);
    acc.add({.triangle = 0,
             .barycentric = {1.f, 0.f, 0.f},
             .value = 2.f,
             .signed_depth = -0.1f,
             .cos_incidence = 0.5f},
            3);
    acc.add({.triangle = 0,
             .barycentric = {0.5f, 0.5f, 0.f},
             .value = 6.f,
             .signed_depth = -0.3f,
             .cos_incidence = 0.9f},
            4);
    AtlasAccumulator other(m, 0.1);
    other.add({.triangle = 1,
               .barycentric = {1.f, 0.f, 0.f},
               .value = 4.f,
               .signed_depth = 0.2f,
               .cos_incidence = 0.7f},
              5);
    acc.merge(other);
    const ZoomAtlas a = acc.finish();
    // Vertex 0 is corner 0 of both triangles.
    EXPECT_EQ(a.count[0], 3u);
    EXPECT_FLOAT_EQ(a.value_max[0], 6.f);
    EXPECT_FLOAT_EQ(a.depth_at_max[0], -0.3f);
    EXPECT_EQ(a.max_view[0], 4);
    EXPECT_EQ(a.best_view[0], 4);
    EXPECT_NEAR(a.value_mean[0], (1.0 * 2 + 0.5 * 6 + 1.0 * 4) / 2.5, 1e-5);
    EXPECT_EQ(a.best_view[2], -1);  // vertex 2 was never observed
    EXPECT_EQ(a.best_view[3], -1);  // vertex 3 only got zero barycentric weight
}

TEST(RobustFloor, IsMedianPlusKScaledMadWithAMinimumAndAPlausibleCap) {
    std::vector<float> v{1, 2, 3, 4, 100};
    std::vector<std::uint8_t> use(v.size(), 1);
    const Floor f = robust_floor(v, use, 3.0, 0.0, 1000.0);
    EXPECT_DOUBLE_EQ(f.median, 3.0);
    EXPECT_DOUBLE_EQ(f.mad, 1.0);
    EXPECT_NEAR(f.value, 3.0 + 3.0 * 1.4826, 1e-12);
    EXPECT_FALSE(f.implausible);
    EXPECT_DOUBLE_EQ(robust_floor(v, use, 3.0, 50.0, 1000.0).value, 50.0);
    // Above the plausible limit: capped and flagged, never silently absurd.
    const Floor capped = robust_floor(v, use, 3.0, 0.0, 5.0);
    EXPECT_TRUE(capped.implausible);
    EXPECT_DOUBLE_EQ(capped.value, 5.0);
}

TEST(FindRegions, KindFollowsThePeakShapeChangeAndMissingSurfaceByMajority) {
    const int n = 10;
    const Mesh m = grid(n);
    const std::size_t nv = m.vertex_count();
    std::vector<float> angle(nv, 0.f), shape(nv, 0.f), missing(nv, 0.f);
    std::vector<std::uint8_t> seen(nv, 1);
    auto id = [n](int x, int y) { return static_cast<std::size_t>(y * (n + 1) + x); };
    // A group mostly positive in its mean but whose largest change is a loss: a dent, so its
    // kind never contradicts the depth it reports.
    for (int x = 1; x <= 3; ++x) {
        angle[id(x, 2)] = 10.f;
        shape[id(x, 2)] = 0.1f;
    }
    shape[id(2, 2)] = -0.5f;
    // A group with no examined surface behind most of it.
    for (int x = 6; x <= 8; ++x) {
        angle[id(x, 7)] = 90.f;
        shape[id(x, 7)] = 0.3f;
        missing[id(x, 7)] = 1.f;
    }
    const RegionResult r = find_regions(m, at_least(angle, 5.f), seen,
                                        {.value = &angle, .shape = &shape, .missing = &missing},
                                        RegionOptions{.fill_holes = false});
    ASSERT_EQ(r.regions.size(), 2u);
    for (const auto& region : r.regions) {
        if (region.centroid.y() < 5) {
            EXPECT_EQ(region.kind, RegionKind::Dent);
            EXPECT_LT(region.peak_depth, 0.0);
        } else {
            EXPECT_EQ(region.kind, RegionKind::MissingSurface);
            EXPECT_NEAR(region.missing_fraction, 1.0, 1e-9);
        }
    }
}

}  // namespace
}  // namespace glint
