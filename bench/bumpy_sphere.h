// The render and sweep benchmarks' surface: a bumpy latitude/longitude sphere (an exact
// analytic shape, no file needed) at any size, with vertex normals, and a ring of views of it.
#pragma once

#include "mesh/mesh.h"
#include "mesh/normals.h"
#include "render/view.h"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace glint::bench {

/// Bumpy UV sphere with 4·rings·(rings − 1) triangles: r = 158 → 99.5k, r = 500 → 998k.
inline Mesh bumpy_sphere(int rings) {
    Mesh mesh;
    const int segments = 2 * rings;
    const double pi = std::numbers::pi;
    const auto point = [&](double theta, double phi) {
        const double r = 1.0 + 0.05 * std::sin(7.0 * theta) * std::cos(5.0 * phi);
        return Vec3f(static_cast<float>(r * std::sin(theta) * std::cos(phi)),
                     static_cast<float>(r * std::sin(theta) * std::sin(phi)),
                     static_cast<float>(r * std::cos(theta)));
    };
    mesh.positions.push_back(point(0.0, 0.0));
    for (int i = 1; i < rings; ++i) {
        for (int j = 0; j < segments; ++j)
            mesh.positions.push_back(point(pi * i / rings, 2.0 * pi * j / segments));
    }
    mesh.positions.push_back(point(pi, 0.0));
    const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
    const auto at = [&](int ring, int seg) {
        return static_cast<std::uint32_t>(1 + (ring - 1) * segments + (seg % segments));
    };
    for (int j = 0; j < segments; ++j) mesh.triangles.push_back({0, at(1, j), at(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    for (int j = 0; j < segments; ++j)
        mesh.triangles.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
    compute_vertex_normals(mesh);
    return mesh;
}

/// `count` views around the mesh: azimuths evenly spaced, elevations spread over ±60°,
/// orthographic, framed to fit, size × size pixels.
inline std::vector<View> ring_views(const Mesh& mesh, int size, int count) {
    std::vector<View> views;
    for (int i = 0; i < count; ++i) {
        views.push_back(
            make_view(mesh, ViewSpec{.azimuth_deg = 360.0 * i / count,
                                     .elevation_deg = -60.0 + 120.0 * ((i * 7) % count) / count,
                                     .width = size,
                                     .height = size,
                                     .index = i}));
    }
    return views;
}

}  // namespace glint::bench
