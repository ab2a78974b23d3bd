// STL reader: binary and ASCII, the "solid" header trap, welding and repair counts, real file.
#include "mesh/error.h"
#include "mesh/io.h"

#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path out_dir() { return test::output_dir("stl_test"); }

fs::path write_bytes(const std::string& name, const std::string& bytes) {
    return test::write_bytes(out_dir(), name, bytes);
}

using Facet = std::array<Vec3f, 3>;

// The unit cube as 12 outward facets.
std::vector<Facet> cube_facets() {
    const Vec3f c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                              {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    std::vector<Facet> out;
    for (const auto& f : faces) out.push_back({c[f[0]], c[f[1]], c[f[2]]});
    return out;
}

std::string binary_stl(const std::vector<Facet>& facets,
                       const std::string& header80 = "glint test") {
    std::string s(80, ' ');
    std::memcpy(s.data(), header80.data(), std::min<std::size_t>(header80.size(), 80));
    const auto n = static_cast<std::uint32_t>(facets.size());
    s.append(reinterpret_cast<const char*>(&n), 4);
    for (const auto& f : facets) {
        const float zero[3] = {0, 0, 0};
        s.append(reinterpret_cast<const char*>(zero), 12);
        for (const auto& v : f) s.append(reinterpret_cast<const char*>(v.data()), 12);
        s.append(2, '\0');
    }
    return s;
}

std::string ascii_stl(const std::vector<Facet>& facets) {
    std::ostringstream s;
    s << "solid cube\n";
    for (const auto& f : facets) {
        s << "  facet normal 0 0 0\n    outer loop\n";
        for (const auto& v : f)
            s << "      vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
        s << "    endloop\n  endfacet\n";
    }
    s << "endsolid cube\n";
    return s.str();
}

TEST(StlReader, WeldsABinaryCubeTo8VerticesCounting28Welds) {
    const LoadedMesh loaded = load_mesh(write_bytes("cube.stl", binary_stl(cube_facets())));
    EXPECT_EQ(loaded.report.format, "stl-binary");
    EXPECT_EQ(loaded.report.reader, MeshReader::FastStl);
    EXPECT_EQ(loaded.report.file_vertices, 36u);
    EXPECT_EQ(loaded.report.file_triangles, 12u);
    // 36 stored corners, 8 distinct positions: 28 corners merged into an earlier one.
    EXPECT_EQ(loaded.report.welded_vertices, 28u);
    EXPECT_EQ(loaded.mesh.vertex_count(), 8u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 12u);
}

TEST(StlReader, ReadsAsciiToTheSameMeshAsBinary) {
    const LoadedMesh bin = load_mesh(write_bytes("cube_b.stl", binary_stl(cube_facets())));
    const LoadedMesh txt = load_mesh(write_bytes("cube_a.stl", ascii_stl(cube_facets())));
    EXPECT_EQ(txt.report.format, "stl-ascii");
    EXPECT_EQ(txt.mesh.positions, bin.mesh.positions);
    EXPECT_EQ(txt.mesh.triangles, bin.mesh.triangles);
    EXPECT_EQ(txt.report.welded_vertices, 28u);
}

TEST(StlReader, ReadsABinaryFileWhoseHeaderStartsWithSolid) {
    const LoadedMesh loaded = load_mesh(
        write_bytes("solid_header.stl", binary_stl(cube_facets(), "solid exported by a CAD tool")));
    EXPECT_EQ(loaded.report.format, "stl-binary");
    EXPECT_EQ(loaded.mesh.vertex_count(), 8u);
}

TEST(StlReader, CountsDuplicateAndDegenerateFacets) {
    auto facets = cube_facets();
    facets.push_back(facets[3]);                                         // exact duplicate
    facets.push_back({Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(2, 0, 0)});  // collinear: zero area
    facets.push_back({Vec3f(0, 0, 0), Vec3f(0, 0, 0), Vec3f(1, 1, 1)});  // repeated corner
    const LoadedMesh loaded = load_mesh(write_bytes("cube_repairs.stl", binary_stl(facets)));
    EXPECT_EQ(loaded.report.file_triangles, 15u);
    EXPECT_EQ(loaded.report.duplicate_triangles, 1u);
    EXPECT_EQ(loaded.report.degenerate_triangles, 2u);
    // (2, 0, 0) is used only by the dropped collinear facet.
    EXPECT_EQ(loaded.report.unused_vertices, 1u);
    EXPECT_EQ(loaded.mesh.vertex_count(), 8u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 12u);
}

TEST(StlReader, FanSplitsAsciiFacetsWithMoreThanThreeVertices) {
    const LoadedMesh loaded = load_mesh(write_bytes(
        "quad.stl",
        "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
        "vertex 0 1 0\nendloop\nendfacet\nendsolid q\n"));
    EXPECT_EQ(loaded.report.split_polygons, 1u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 2u);
    EXPECT_EQ(loaded.mesh.vertex_count(), 4u);
}

TEST(StlReader, LoadsARealMolarWithTheReadmeCounts) {
    const auto path =
        fs::path(GLINT_SHARED_DATA_DIR) / "teeth_cbct_openfulljaw/Patient_26_tooth_19.stl";
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not present: " << path;
    const LoadedMesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.report.format, "stl-binary");
    EXPECT_EQ(loaded.report.file_triangles, 43980u);
    EXPECT_EQ(loaded.mesh.vertex_count(), 21992u);  // README: after welding identical corners
    EXPECT_EQ(loaded.mesh.triangle_count(), 43980u);
    EXPECT_EQ(loaded.report.welded_vertices, 3u * 43980u - 21992u);
}

}  // namespace
}  // namespace glint
