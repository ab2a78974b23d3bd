#include "mesh/reorder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

namespace glint {
namespace {

// A grid of quads with its triangles shuffled, so reordering has something to do.
Mesh shuffled_grid(int n) {
    Mesh m;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) m.positions.emplace_back(float(x), float(y), 0.f);
    auto id = [n](int x, int y) { return static_cast<std::uint32_t>(y * (n + 1) + x); };
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            m.triangles.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1)});
            m.triangles.push_back({id(x, y), id(x + 1, y + 1), id(x, y + 1)});
        }
    std::mt19937 rng(42);
    std::shuffle(m.triangles.begin(), m.triangles.end(), rng);
    m.labels.resize(m.positions.size());
    std::iota(m.labels.begin(), m.labels.end(), 0);
    m.positions.emplace_back(99.f, 99.f, 99.f);  // unused vertex must survive reordering
    m.labels.push_back(-1);
    return m;
}

TEST(ReorderForLocality, KeepsTheSameSurfaceAndMapsBackToOriginalIds) {
    const Mesh original = shuffled_grid(20);
    Mesh m = original;
    const ReorderMap map = reorder_for_locality(m);
    ASSERT_EQ(m.positions.size(), original.positions.size());
    ASSERT_EQ(m.triangles.size(), original.triangles.size());
    // Every vertex keeps its position and attributes under the map.
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
        EXPECT_EQ(m.positions[v], original.positions[map.original_vertex[v]]);
        EXPECT_EQ(m.labels[v], original.labels[map.original_vertex[v]]);
    }
    // Every triangle is the original triangle it maps to, up to rotation of its corners.
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        const auto& o = original.triangles[map.original_triangle[t]];
        Triangle mapped;
        for (int k = 0; k < 3; ++k)
            mapped[static_cast<std::size_t>(k)] =
                map.original_vertex[m.triangles[t][static_cast<std::size_t>(k)]];
        const bool same = (mapped == o) || (mapped == Triangle{o[1], o[2], o[0]}) ||
                          (mapped == Triangle{o[2], o[0], o[1]});
        EXPECT_TRUE(same) << "triangle " << t;
    }
    // Scattering back restores the original order.
    std::vector<float> values(m.positions.size());
    for (std::size_t v = 0; v < values.size(); ++v) values[v] = static_cast<float>(m.labels[v]);
    const auto back = to_original_order(map, values);
    for (std::size_t v = 0; v < back.size(); ++v)
        EXPECT_EQ(back[v], static_cast<float>(original.labels[v]));
}

}  // namespace
}  // namespace glint
