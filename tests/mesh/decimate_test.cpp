// Decimation for display (mesh/decimate.h): the budget is met, every vertex is an input vertex
// at its place, kept triangles come through exactly, borders do not move.
#include "mesh/decimate.h"

#include "mesh/components.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace glint {
namespace {

std::set<std::array<std::uint32_t, 3>> as_input_triangles(const DecimatedMesh& d) {
    std::set<std::array<std::uint32_t, 3>> out;
    for (const auto& t : d.mesh.triangles)
        out.insert({d.original_vertex[t[0]], d.original_vertex[t[1]], d.original_vertex[t[2]]});
    return out;
}

TEST(Decimate, MeetsTheBudgetWithInputVerticesAndKeepsTheMarkedTriangles) {
    const Mesh sphere = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 5});
    std::vector<std::uint8_t> keep(sphere.triangle_count(), 0);
    std::size_t kept = 0;
    for (std::size_t t = 0; t < sphere.triangle_count(); ++t)
        if (sphere.positions[sphere.triangles[t][0]].x() > 9.0f) {
            keep[t] = 1;
            ++kept;
        }
    ASSERT_GT(kept, 50u);
    const DecimatedMesh d = decimate(sphere, 2000, keep, 1.0);
    EXPECT_LE(d.mesh.triangle_count(), 2000u + 100u);
    EXPECT_GT(d.mesh.triangle_count(), 1000u);
    ASSERT_EQ(d.original_vertex.size(), d.mesh.vertex_count());
    ASSERT_EQ(d.mesh.normals.size(), d.mesh.vertex_count());
    for (std::size_t k = 0; k < d.mesh.vertex_count(); ++k) {
        ASSERT_LT(d.original_vertex[k], sphere.vertex_count());
        EXPECT_EQ(d.mesh.positions[k], sphere.positions[d.original_vertex[k]]);
        EXPECT_EQ(d.mesh.normals[k], sphere.normals[d.original_vertex[k]]);
    }
    const auto triangles = as_input_triangles(d);
    for (std::size_t t = 0; t < sphere.triangle_count(); ++t)
        if (keep[t]) {
            EXPECT_TRUE(triangles.count(sphere.triangles[t])) << "kept triangle " << t << " lost";
        }
    // Still a closed surface: collapses never open it.
    const auto open = border_vertices(d.mesh);
    EXPECT_EQ(std::count(open.begin(), open.end(), 1), 0);
    EXPECT_GT(d.error, 0.0);
    EXPECT_LT(d.error, 1.0);
}

TEST(Decimate, BordersStayPutAndASmallMeshIsLeftAlone) {
    Mesh half = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Uv, .resolution = 60});
    std::vector<Triangle> upper;
    for (const auto& t : half.triangles)
        if (half.positions[t[0]].z() > 0 && half.positions[t[1]].z() > 0 &&
            half.positions[t[2]].z() > 0)
            upper.push_back(t);
    half.triangles = upper;
    const auto border = border_vertices(half);
    const DecimatedMesh d = decimate(half, half.triangle_count() / 10, {}, 1.0);
    EXPECT_LT(d.mesh.triangle_count(), half.triangle_count() / 5);
    std::set<std::uint32_t> shown(d.original_vertex.begin(), d.original_vertex.end());
    for (std::size_t v = 0; v < half.vertex_count(); ++v)
        if (border[v]) {
            EXPECT_TRUE(shown.count(static_cast<std::uint32_t>(v)))
                << "border vertex " << v << " moved";
        }
    const DecimatedMesh same = decimate(half, half.triangle_count(), {}, 1.0);
    EXPECT_EQ(same.mesh.triangle_count(), half.triangle_count());
    EXPECT_EQ(same.error, 0.0);
}

TEST(Decimate, InPiecesTheSurfaceStaysClosedAndMeetsTheBudget) {
    const Mesh sphere = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 5});
    const DecimatedMesh d = decimate(sphere, 3000, {}, 1.0, 4000);  // 20480 triangles in 6 slabs
    EXPECT_LE(d.mesh.triangle_count(), 3000u + 150u);
    EXPECT_GT(d.mesh.triangle_count(), 1500u);
    const auto open = border_vertices(d.mesh);
    EXPECT_EQ(std::count(open.begin(), open.end(), 1), 0) << "the slabs do not join";
    for (std::size_t k = 0; k < d.mesh.vertex_count(); ++k)
        ASSERT_EQ(d.mesh.positions[k], sphere.positions[d.original_vertex[k]]);
}

}  // namespace
}  // namespace glint
