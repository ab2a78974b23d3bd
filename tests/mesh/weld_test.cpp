#include "mesh/weld.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// Triangle soup of a unit cube: 12 facets, 36 corners, 8 distinct positions.
Mesh cube_soup() {
    const Vec3f c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                              {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    Mesh m;
    for (const auto& f : faces) {
        const auto base = static_cast<std::uint32_t>(m.positions.size());
        for (int k : f) m.positions.push_back(c[k]);
        m.triangles.push_back({base, base + 1, base + 2});
    }
    return m;
}

TEST(WeldVertices, CubeSoupWeldsTo8VerticesAndCounts28Merges) {
    Mesh m = cube_soup();
    RepairCounts counts;
    weld_vertices(m, counts);
    EXPECT_EQ(m.positions.size(), 8u);
    EXPECT_EQ(counts.welded_vertices, 36u - 8u);
    EXPECT_EQ(m.triangles.size(), 12u);
}

TEST(WeldVertices, TreatsNegativeZeroAsZero) {
    Mesh m;
    m.positions = {{0.0f, 1, 2}, {-0.0f, 1, 2}, {3, 4, 5}};
    RepairCounts counts;
    weld_vertices(m, counts);
    EXPECT_EQ(m.positions.size(), 2u);
    EXPECT_EQ(counts.welded_vertices, 1u);
}

TEST(WeldVertices, CarriesPerVertexAttributesOfFirstOccurrence) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}};
    m.labels = {7, 8, 9};
    m.scalars.push_back({"s", {1.f, 2.f, 3.f}});
    m.triangles = {{2, 1, 0}};
    RepairCounts counts;
    const auto map = weld_vertices(m, counts);
    ASSERT_EQ(m.positions.size(), 2u);
    EXPECT_EQ(map[2], 0u);
    EXPECT_EQ(m.labels, (std::vector<std::int32_t>{7, 8}));
    EXPECT_EQ(m.scalars[0].values, (std::vector<float>{1.f, 2.f}));
    EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 0}));
}

TEST(DropDegenerateTriangles, CountsRepeatedVertexZeroAreaAndDuplicates) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
    m.triangles = {
        {0, 1, 2},  // kept
        {1, 2, 0},  // same triangle rotated: duplicate
        {0, 2, 1},  // opposite winding: kept (a two-sided sheet is not a duplicate)
        {0, 0, 1},  // repeated vertex
        {0, 1, 3},  // collinear: zero area
    };
    RepairCounts counts;
    drop_degenerate_triangles(m, counts);
    EXPECT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(counts.degenerate_triangles, 2u);
    EXPECT_EQ(counts.duplicate_triangles, 1u);
}

TEST(DropUnusedVertices, RemovesUnreferencedAndReindexes) {
    Mesh m;
    m.positions = {{9, 9, 9}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {8, 8, 8}};
    m.labels = {0, 1, 2, 3, 4};
    m.triangles = {{1, 2, 3}};
    RepairCounts counts;
    const auto map = drop_unused_vertices(m, counts);
    EXPECT_EQ(counts.unused_vertices, 2u);
    EXPECT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2}));
    EXPECT_EQ(m.labels, (std::vector<std::int32_t>{1, 2, 3}));
    EXPECT_EQ(map[0], kInvalidVertex);
    EXPECT_EQ(map[4], kInvalidVertex);
}

}  // namespace
}  // namespace glint
