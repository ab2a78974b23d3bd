#include "mesh/remesh.h"

#include "mesh/components.h"
#include "mesh/error.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

Mesh sphere(int level) {
    return make_phantom({.kind = PhantomKind::Sphere,
                         .scheme = TessellationScheme::Ico,
                         .resolution = level,
                         .radii = {10, 10, 10}});
}

TEST(Remesh, KeepsTheSurfaceAndReachesTheTargetEdge) {
    const Mesh input = sphere(4);
    const EdgeStats before = edge_stats(input);
    const double target = 0.5 * before.median;
    const Mesh out = remesh_isotropic(input, {target, 3});
    const EdgeStats after = edge_stats(out);
    EXPECT_NEAR(after.median, target, 0.2 * target);
    EXPECT_GT(out.vertex_count(), 3 * input.vertex_count());
    // Vertices are projected onto the input: on its triangles, so inside the sphere by at most
    // the depth of a triangle's circumcentre (circumradius ≈ edge/√3 on the near-equilateral
    // icosphere), never outside it.
    const double sagitta =
        10.0 - 10.0 * std::cos(std::asin(before.max / std::sqrt(3.0) / 10.0)) + 1e-4;
    for (const auto& p : out.positions) {
        const double r = p.cast<double>().norm();
        EXPECT_LE(r, 10.0 + 1e-4);
        EXPECT_GE(r, 10.0 - sagitta);
    }
    // Still closed, one piece, with normals.
    const auto border = border_vertices(out);
    EXPECT_EQ(std::count(border.begin(), border.end(), 1), 0);
    EXPECT_TRUE(out.has_normals());
    EXPECT_NEAR(surface_area(out), surface_area(input), 0.01 * surface_area(input));
}

TEST(Remesh, RefusesBadInputWithOneLine) {
    EXPECT_THROW((void)remesh_isotropic(Mesh{}, {1.0, 3}), InputError);
    EXPECT_THROW((void)remesh_isotropic(sphere(1), {0.0, 3}), InputError);
    EXPECT_THROW((void)remesh_isotropic(sphere(1), {1.0, 0}), InputError);
    Mesh fan = sphere(1);
    // Three triangles on one edge: not a polygon mesh.
    fan.positions.push_back({0, 0, 30});
    fan.triangles.push_back({fan.triangles[0][0], fan.triangles[0][1],
                             static_cast<std::uint32_t>(fan.vertex_count() - 1)});
    try {
        (void)remesh_isotropic(fan, {1.0, 3});
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("manifold"), std::string::npos) << e.what();
    }
}

TEST(Shuffle, SameSurfaceOtherOrder) {
    Mesh m = sphere(3);
    m.set_scalar("height", [&] {
        std::vector<float> h;
        for (const auto& p : m.positions) h.push_back(p.z());
        return h;
    }());
    const Mesh before = m;
    shuffle_mesh(m, 42);
    ASSERT_EQ(m.vertex_count(), before.vertex_count());
    ASSERT_EQ(m.triangle_count(), before.triangle_count());
    std::size_t moved = 0;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        moved += m.positions[v] != before.positions[v];
        EXPECT_EQ(m.find_scalar("height")->values[v],
                  m.positions[v].z());  // fields follow their vertex
    }
    EXPECT_GT(moved, m.vertex_count() / 2);
    EXPECT_NEAR(surface_area(m), surface_area(before), 1e-6 * surface_area(before));
    // Orientation kept: the signed volume is unchanged.
    auto volume = [](const Mesh& x) {
        double s = 0;
        for (const auto& t : x.triangles)
            s += x.positions[t[0]].cast<double>().dot(
                x.positions[t[1]].cast<double>().cross(x.positions[t[2]].cast<double>()));
        return s / 6;
    };
    EXPECT_NEAR(volume(m), volume(before), 1e-6 * std::abs(volume(before)));
}

TEST(EdgeStats, CountsEachEdgeOnce) {
    const Mesh m = sphere(0);  // icosahedron: 30 equal edges
    const EdgeStats s = edge_stats(m);
    EXPECT_EQ(s.edges, 30u);
    EXPECT_NEAR(s.min, s.max, 1e-4);
    EXPECT_NEAR(s.mean, s.median, 1e-4);
}

}  // namespace
}  // namespace glint
