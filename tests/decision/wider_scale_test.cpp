// The search over wider rungs (decision.cpp search_wider) and the sparse reading it rests on
// (decision/detail/evidence_scale.h sparse_scaled_evidence), on a flat grid whose distance is
// smooth noise (blobs of σ 3 units, like a CT's correlated noise: it averages down only over
// discs wider than its grain) with, or without, a wide shallow dent.
#include "decision/decision.h"
#include "decision/detail/evidence_scale.h"
#include "mesh/normals.h"
#include "tests/decision/flat_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace glint {
namespace {

constexpr int kN = 120;  // kN × kN unit squares

struct NoisyGrid : test::FlatEvidence {
    static std::uint32_t id(int x, int y) { return test::grid_vertex(kN, x, y); }

    /// Noise blobs of amplitude up to ±amplitude/2 every 2 units; a Gaussian dent of `depth`
    /// and σ `width` at the centre.
    NoisyGrid(float amplitude, float depth, float width) : FlatEvidence(kN) {
        compute_vertex_normals(mesh);
        std::uint32_t state = 777;
        auto uniform = [&state] {  // in [-0.5, 0.5): a fixed linear congruential sequence
            state = state * 1664525u + 1013904223u;
            return static_cast<float>(state >> 8) / static_cast<float>(1u << 24) - 0.5f;
        };
        for (int by = 0; by <= kN; by += 2)
            for (int bx = 0; bx <= kN; bx += 2) {
                const float a = amplitude * uniform();
                for (int y = std::max(0, by - 9); y <= std::min(kN, by + 9); ++y)
                    for (int x = std::max(0, bx - 9); x <= std::min(kN, bx + 9); ++x)
                        distance[id(x, y)] +=
                            a * std::exp(-float((x - bx) * (x - bx) + (y - by) * (y - by)) / 18.f);
            }
        const double c = kN / 2.0;
        for (int y = 0; y <= kN; ++y)
            for (int x = 0; x <= kN; ++x)
                distance[id(x, y)] -=
                    static_cast<float>(depth * std::exp(-((x - c) * (x - c) + (y - c) * (y - c)) /
                                                        (2 * width * width)));
    }

    /// The scans' voxel is 3 units: the ladder starts at 4√2 (the median edge is √2).
    [[nodiscard]] DecisionEvidence view() const { return FlatEvidence::view(3.0, 400.0); }
};

// A dent 1.4 deep and wide (σ 12) under smooth noise: at the finest quiet rung its smoothed peak
// stays shallower than what the run states it can tell there, so only a wider rung, where the
// noise has averaged down, finds it; it is reported with the radius that found it, at its
// place, with that scale's spread as its ±. Without the dent no rung finds anything.
TEST(Decide, AWideShallowChangeBelowTheChosenScalesLimitIsFoundOverAWiderDisc) {
    const NoisyGrid clean(0.3f, 0.0f, 12.0f);
    const ZoomDecision none = decide(clean.mesh, clean.view(), DecisionOptions{});
    EXPECT_TRUE(none.scale.quiet);
    EXPECT_EQ(none.scale.wider.size(), 2u) << "two rungs beyond the chosen one";
    EXPECT_TRUE(none.regions.regions.empty());
    EXPECT_TRUE(none.warnings.empty()) << none.warnings.front();

    const NoisyGrid dented(0.3f, 1.4f, 12.0f);
    const ZoomDecision d = decide(dented.mesh, dented.view(), DecisionOptions{});
    ASSERT_EQ(d.regions.regions.size(), 1u) << d.scale.text;
    const Region& r = d.regions.regions[0];
    EXPECT_EQ(r.kind, RegionKind::Dent);
    EXPECT_NEAR(r.centroid.x(), kN / 2.0, 3.0);
    EXPECT_NEAR(r.centroid.y(), kN / 2.0, 3.0);
    EXPECT_GT(r.scale_radius, d.scale.radius) << "found over a wider disc than the chosen one";
    EXPECT_GT(d.scale.min_depth, 1.4) << "the chosen rung states it cannot tell 1.4 deep";
    EXPECT_NE(r.evidence.find("a wider rung"), std::string::npos) << r.evidence;
    ASSERT_TRUE(std::isfinite(r.depth_sd));
    EXPECT_LT(r.depth_sd, 1.4826 * d.shape.mad) << "the wider disc's spread is the smaller";
    EXPECT_LT(r.p_value, 1e-3);
    EXPECT_NE(d.rule_text.find("p values count the 3 scales searched"), std::string::npos)
        << d.rule_text;
    // The dent itself is no unreported change: the region holds it.
    EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();

    // A surface against its mirror image differs by nature, most over wide discs: natural
    // floors are read at the chosen scale only.
    DecisionOptions natural;
    natural.natural_floors = true;
    const ZoomDecision mirror = decide(dented.mesh, dented.view(), natural);
    EXPECT_TRUE(mirror.scale.searched);
    EXPECT_TRUE(mirror.scale.wider.empty());
}

// The sparse reading gives the full reading's field at a wide radius: fitted on one vertex per
// cell of a quarter radius, the others take their nearest fitted neighbour's value.
TEST(SparseScaledEvidence, GivesTheFullReadingsFieldAtAWideRadius) {
    const NoisyGrid g(0.3f, 1.2f, 16.0f);
    const DecisionEvidence e = g.view();
    const double r = 8.0 * std::sqrt(2.0);
    const detail::ScaledEvidence full = detail::scaled_evidence(g.mesh, e, r);
    const detail::ScaledEvidence sparse = detail::sparse_scaled_evidence(g.mesh, e, r);
    ASSERT_EQ(sparse.distance.size(), full.distance.size());
    double spread = 0.0;
    std::vector<double> off, tilt_off;
    for (std::size_t v = 0; v < full.distance.size(); ++v) {
        ASSERT_TRUE(std::isfinite(sparse.distance[v])) << "vertex " << v;
        spread = std::max(spread, double(std::abs(full.distance[v])));
        off.push_back(std::abs(sparse.distance[v] - full.distance[v]));
        tilt_off.push_back(std::abs(sparse.tilt_deg[v] - full.tilt_deg[v]));
    }
    EXPECT_GT(spread, 0.9) << "the dent's 1.2 survives the reading";
    // Within a twentieth of the field's reach at 99 % of the vertices, a fifth at all (the
    // grid's edges, where a one-sided disc turns fastest, are the worst).
    std::sort(off.begin(), off.end());
    std::sort(tilt_off.begin(), tilt_off.end());
    const std::size_t p99 = off.size() * 99 / 100;
    EXPECT_LT(off[p99], 0.05 * spread);
    EXPECT_LT(off.back(), 0.2 * spread);
    // A vertex keeps its source's tilt: within a degree at 99 % (the dent tilts by up to 3.5°).
    EXPECT_LT(tilt_off[tilt_off.size() / 2], 0.3) << "degrees";
    EXPECT_LT(tilt_off[p99], 1.0) << "degrees";
    EXPECT_LT(tilt_off.back(), 2.0) << "degrees";
}

}  // namespace
}  // namespace glint
