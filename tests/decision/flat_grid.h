// A flat grid mesh for the decision's tests: n × n unit squares in the z = 0 plane, each cut
// into two triangles along its diagonal ((n + 1)² vertices, row by row). Half the triangles'
// first edges are diagonals, so the median edge the ladder reads is √2.
#pragma once

#include "mesh/mesh.h"

#include <cstdint>

namespace glint::test {

[[nodiscard]] inline std::uint32_t grid_vertex(int n, int x, int y) {
    return static_cast<std::uint32_t>(y * (n + 1) + x);
}

[[nodiscard]] inline Mesh flat_grid(int n) {
    Mesh m;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) m.positions.emplace_back(float(x), float(y), 0.f);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            m.triangles.push_back(
                {grid_vertex(n, x, y), grid_vertex(n, x + 1, y), grid_vertex(n, x + 1, y + 1)});
            m.triangles.push_back(
                {grid_vertex(n, x, y), grid_vertex(n, x + 1, y + 1), grid_vertex(n, x, y + 1)});
        }
    return m;
}

}  // namespace glint::test
