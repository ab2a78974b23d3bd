#include "mesh/validate.h"

#include "mesh/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace glint {
namespace {

Mesh tetrahedron() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return m;
}

// Expects InputError whose message contains every fragment.
template <class F>
void expect_input_error(F&& f, std::initializer_list<const char*> fragments) {
    try {
        f();
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        for (const char* frag : fragments) EXPECT_NE(msg.find(frag), std::string::npos) << msg;
    }
}

TEST(CheckMesh, AcceptsClosedTetrahedron) {
    const auto report = validate_mesh(tetrahedron(), "tet");
    EXPECT_TRUE(report.is_closed);
    EXPECT_EQ(report.components, 1u);
    EXPECT_EQ(report.boundary_edges, 0u);
    EXPECT_TRUE(report.findings.empty());
}

TEST(CheckMesh, RejectsNaNCoordinateNamingVertex) {
    Mesh m = tetrahedron();
    m.positions[2].y() = std::numeric_limits<float>::quiet_NaN();
    expect_input_error([&] { check_mesh(m, "bad.ply"); }, {"bad.ply", "vertex 2", "non-finite"});
}

TEST(CheckMesh, RejectsIndexPastTheEndNamingTriangle) {
    Mesh m = tetrahedron();
    m.triangles[3][1] = 4;
    expect_input_error([&] { check_mesh(m, "bad.ply"); },
                       {"bad.ply", "triangle 3", "vertex 4", "4 vertices"});
}

TEST(CheckMesh, RejectsMeshWithoutTriangles) {
    Mesh m = tetrahedron();
    m.triangles.clear();
    expect_input_error([&] { check_mesh(m, "pts.ply"); }, {"pts.ply", "no triangles"});
}

TEST(CheckMesh, RejectsEmptyMesh) {
    expect_input_error([&] { check_mesh(Mesh{}, "empty.ply"); }, {"empty.ply", "no vertices"});
}

TEST(CheckMesh, RejectsZeroExtent) {
    Mesh m;
    m.positions = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
    m.triangles = {{0, 1, 2}};
    expect_input_error([&] { check_mesh(m, "dot.ply"); }, {"dot.ply", "zero extent"});
}

TEST(ValidateMesh, ReportsBoundaryNonManifoldAndComponents) {
    Mesh m = tetrahedron();
    m.triangles.pop_back();  // open: 3 boundary edges
    // A second component: a fin sharing nothing, and a non-manifold edge (three triangles
    // on the edge 4-5).
    m.positions.insert(m.positions.end(), {{5, 0, 0}, {6, 0, 0}, {5, 1, 0}, {5, -1, 0}, {5, 0, 1}});
    m.triangles.insert(m.triangles.end(), {{4, 5, 6}, {5, 4, 7}, {4, 5, 8}});
    const auto report = validate_mesh(m, "mixed");
    EXPECT_EQ(report.components, 2u);
    EXPECT_EQ(report.non_manifold_edges, 1u);
    EXPECT_EQ(report.boundary_edges, 3u + 6u);
    EXPECT_FALSE(report.is_closed);
    EXPECT_EQ(report.findings.size(), 3u);
}

TEST(ValidateMesh, CountsUnusedVertices) {
    Mesh m = tetrahedron();
    m.positions.push_back({3, 3, 3});
    const auto report = validate_mesh(m, "extra");
    EXPECT_EQ(report.unused_vertices, 1u);
}

}  // namespace
}  // namespace glint
