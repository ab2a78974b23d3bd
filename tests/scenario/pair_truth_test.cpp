#include "scenario/pair_truth.h"

#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "mesh/remesh.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

Mesh sphere(int level) {
    return make_phantom({.kind = PhantomKind::Sphere,
                         .scheme = TessellationScheme::Ico,
                         .resolution = level,
                         .radii = {10, 10, 10}});
}

DamageSpec dent(const Vec3d& c, double radius, double depth) {
    DamageSpec d;
    d.kind = DamageKind::Dent;
    d.center = c;
    d.radius = radius;
    d.depth = depth;
    return d;
}

TEST(PairTruth, DamagedWhereTheSurfaceMovedByATenthOfTheDepth) {
    const Mesh reference = sphere(5);
    Mesh examined = remesh_isotropic(reference, {0.3, 3});
    const std::vector<DamageSpec> damages{dent({0, 0, 10}, 3.0, 0.5), dent({10, 0, 0}, 2.0, 0.2)};
    apply_damage(examined, damages);
    Mesh footprint = reference;
    apply_damage(footprint, damages);
    const PairTruth truth = distance_truth(reference, examined, footprint.labels, damages);
    const auto distance = vertex_distances(reference, examined);
    std::size_t first = 0, second = 0;
    for (std::size_t v = 0; v < reference.vertex_count(); ++v) {
        const auto id = truth.damage_id[v];
        EXPECT_EQ(truth.damaged[v], id > 0 ? 1 : 0);
        if (id == 1) {
            ++first;
            EXPECT_GT(distance[v], 0.05);
        }
        if (id == 2) {
            ++second;
            EXPECT_GT(distance[v], 0.02);
        }
        // Far from both damages nothing is damaged, whatever the tessellation difference.
        const Vec3d p = reference.positions[v].cast<double>();
        if ((p - Vec3d(0, 0, 10)).norm() > 3.5 && (p - Vec3d(10, 0, 0)).norm() > 2.5) {
            EXPECT_EQ(id, 0);
        }
    }
    EXPECT_GT(first, 20u);
    EXPECT_GT(second, 5u);
}

TEST(PairTruth, TallyCountsFalseRegionsAndDetectedDamages) {
    PairTruth truth;
    truth.damaged = {1, 1, 0, 0, 1, 0};
    truth.damage_id = {1, 1, 0, 0, 2, 0};
    // Region 1 covers damage 1, region 2 lies where nothing changed; damage 2 is missed.
    const std::vector<std::int32_t> regions{1, 0, 0, 2, 0, 0};
    const std::vector<float> distance{0.5f, 0.4f, 0.0f, 0.01f, 0.3f, 0.0f};
    const RegionTally t = tally_regions(regions, &truth, distance, 0.1);
    EXPECT_EQ(t.regions, 2u);
    EXPECT_EQ(t.false_regions, 1u);
    EXPECT_EQ(t.damages, 2u);
    EXPECT_EQ(t.damages_detected, 1u);
    EXPECT_EQ(t.close_region_vertices, 1u);  // vertex 3: in a region, 0.01 from the surface
}

TEST(PairTruth, BaselineThresholdsTheDistanceIntoComponents) {
    const Mesh m = sphere(3);
    std::vector<float> distance(m.vertex_count(), 0.0f);
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        const auto& p = m.positions[v];
        if (p.z() > 9.0f) distance[v] = -0.3f;  // a cap at the top
        if (p.z() < -9.0f) distance[v] = 0.3f;  // and one at the bottom
    }
    const BaselineResult b = distance_baseline(m, distance, 0.1);
    EXPECT_EQ(b.regions, 2u);
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
        EXPECT_EQ(b.region_of_vertex[v] != 0, std::abs(distance[v]) > 0.1f);
}

}  // namespace
}  // namespace glint
