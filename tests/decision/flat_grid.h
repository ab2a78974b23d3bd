// A flat grid mesh for the decision's tests: n × n unit squares in the z = 0 plane, each cut
// into two triangles along its diagonal ((n + 1)² vertices, row by row). Half the triangles'
// first edges are diagonals, so the median edge the ladder reads is √2. And evidence over it:
// every vertex seen, normal evidence 1°, the distance 0 until a test writes it.
#pragma once

#include "decision/decision.h"
#include "mesh/mesh.h"
#include "scanner/atlas.h"
#include "scanner/coverage.h"

#include <cstdint>
#include <string>
#include <vector>

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

/// Evidence of one zoom over flat_grid(n) (above); the test writes the distance.
struct FlatEvidence {
    Mesh mesh;
    ZoomAtlas atlas;
    Coverage coverage;
    std::vector<float> distance;
    std::vector<float> tolerance;
    std::vector<std::uint8_t> at_border;

    explicit FlatEvidence(int n) : mesh(flat_grid(n)) {
        const std::size_t count = mesh.vertex_count();
        atlas.value_mean.assign(count, 1.0f);
        atlas.value_max.assign(count, 1.0f);
        atlas.missing.assign(count, 0.0f);
        atlas.depth_mean.assign(count, 0.0f);
        atlas.max_view.assign(count, 0);
        coverage.seen.assign(count, 1);
        coverage.fraction = 1.0;
        distance.assign(count, 0.0f);
        tolerance.assign(count, 0.0f);
        at_border.assign(count, 0);
    }

    /// The scans' voxel `voxel` (mesh units), the reference `size` across, in millimetres.
    [[nodiscard]] DecisionEvidence view(double voxel, double size) const {
        return {.atlas = &atlas,
                .coverage = &coverage,
                .distance = &distance,
                .tolerance = &tolerance,
                .at_border = &at_border,
                .voxel = voxel,
                .metric = Metric::AngleDeg,
                .size = size,
                .unit = "mm"};
    }
};

}  // namespace glint::test
