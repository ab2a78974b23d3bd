#include "registration/closest_point.h"

#include "mesh/phantom.h"

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

TEST(ClosestPointIndex, FindsTheNearestSurfacePointWithItsSign) {
    const Mesh m = sphere(5);
    const ClosestPointIndex index(m);
    // The flat facets lie inside the sphere by at most their sagitta, r²/2R for a facet of
    // circumradius r: ~0.24 mm at level 5 gives 0.003 mm (measured 0.00285).
    constexpr double kSagitta = 0.004;
    for (const Vec3d& dir :
         {Vec3d(1, 0, 0), Vec3d(0.3, -0.5, 0.8).normalized(), Vec3d(-1, -1, -1).normalized()}) {
        const ClosestPoint out = index.closest(13.0 * dir);
        ASSERT_TRUE(out.found);
        EXPECT_NEAR(out.distance, 3.0, kSagitta);
        EXPECT_GT(out.signed_distance, 0.0);
        const ClosestPoint in = index.closest(6.0 * dir);
        EXPECT_NEAR(in.signed_distance, -4.0, kSagitta);
        EXPECT_GT(out.normal.dot(dir), 0.999);
        EXPECT_NEAR(out.barycentric.sum(), 1.0, 1e-12);
    }
}

TEST(ClosestPointIndex, SignIsRobustAtVerticesAndEdges) {
    // Points just outside and inside every vertex and every edge midpoint: the closest
    // feature is a vertex or an edge, where face normals alone disagree.
    const Mesh m = sphere(2);
    const ClosestPointIndex index(m);
    std::size_t wrong = 0;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        const Vec3d p = m.positions[v].cast<double>();
        wrong += index.closest(p * 1.01).signed_distance <= 0;
        wrong += index.closest(p * 0.99).signed_distance >= 0;
    }
    for (const auto& t : m.triangles) {
        const Vec3d mid = 0.5 * (m.positions[t[0]] + m.positions[t[1]]).cast<double>();
        wrong += index.closest(mid * 1.01).signed_distance <= 0;
        wrong += index.closest(mid * 0.99).signed_distance >= 0;
    }
    EXPECT_EQ(wrong, 0u);
}

TEST(ClosestPointIndex, RespectsTheQueryRadius) {
    const ClosestPointIndex index(sphere(3));
    EXPECT_FALSE(index.closest({20, 0, 0}, 5.0).found);
    EXPECT_TRUE(index.closest({20, 0, 0}, 10.5).found);
}

TEST(ClosestPointIndex, BatchQueriesMatchSingleQueries) {
    const ClosestPointIndex index(sphere(3));
    std::vector<Vec3d> q;
    for (int i = 0; i < 5000; ++i)
        q.emplace_back(std::sin(i) * 12, std::cos(i * 0.7) * 9, std::sin(i * 1.3) * 11);
    const auto batch = index.closest(q);
    for (std::size_t i = 0; i < q.size(); i += 97)
        EXPECT_EQ(batch[i].triangle, index.closest(q[i]).triangle);
}

TEST(ClosestPointIndex, ABorrowingIndexAnswersAsACopyingOne) {
    const Mesh m = sphere(3);
    const ClosestPointIndex copy(m);
    const ClosestPointIndex borrowed = ClosestPointIndex::borrowing(m);
    EXPECT_EQ(&borrowed.mesh(), &m);
    EXPECT_NE(&copy.mesh(), &m);
    for (int i = 0; i < 500; ++i) {
        const Vec3d q(std::sin(i) * 12, std::cos(i * 0.7) * 9, std::sin(i * 1.3) * 11);
        const ClosestPoint a = copy.closest(q), b = borrowed.closest(q);
        EXPECT_EQ(a.triangle, b.triangle);
        EXPECT_EQ(a.signed_distance, b.signed_distance);
        EXPECT_EQ(a.normal, b.normal);
    }
}

TEST(Pick, ThePixelAtTheImageCentreShowsTheNearestPoint) {
    const Mesh m = sphere(4);
    const ClosestPointIndex index(m);
    Camera cam;
    cam.world_from_camera = look_at({30, 0, 0}, {0, 0, 0}, {0, 0, 1});
    cam.width = cam.height = 64;
    cam.ortho_half_height = 12;
    const RayHit hit = pick(index, cam, 32, 32);
    ASSERT_TRUE(hit.hit);
    EXPECT_NEAR(hit.point.x(), 10.0, 0.01);
    EXPECT_NEAR(hit.t, 20.0, 0.01);
    EXPECT_FALSE(pick(index, cam, 0.5, 0.5).hit);  // the corner sees past the sphere
}

}  // namespace
}  // namespace glint
