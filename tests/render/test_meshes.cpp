#include "tests/render/test_meshes.h"

#include "mesh/normals.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace glint::test {

Mesh make_icosphere(int level, double radius) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3d> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                            {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                            {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& v : p) v.normalize();
    std::vector<Triangle> tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                  {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                  {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                  {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            p.push_back((p[a] + p[b]).normalized());
            const auto id = static_cast<std::uint32_t>(p.size() - 1);
            mid.emplace(key, id);
            return id;
        };
        std::vector<Triangle> next;
        next.reserve(tris.size() * 4);
        for (const auto& tri : tris) {
            const auto a = midpoint(tri[0], tri[1]);
            const auto b = midpoint(tri[1], tri[2]);
            const auto c = midpoint(tri[2], tri[0]);
            next.push_back({tri[0], a, c});
            next.push_back({tri[1], b, a});
            next.push_back({tri[2], c, b});
            next.push_back({a, b, c});
        }
        tris = std::move(next);
    }
    Mesh mesh;
    for (const auto& v : p) {
        mesh.positions.push_back((radius * v).cast<float>());
        mesh.normals.push_back(v.cast<float>());
    }
    mesh.triangles = std::move(tris);
    return mesh;
}

Mesh make_uv_sphere(int rings, double radius) {
    Mesh mesh;
    const int segments = 2 * rings;
    const double pi = std::numbers::pi;
    mesh.positions.push_back(Vec3f(0, 0, static_cast<float>(radius)));
    mesh.normals.push_back(Vec3f(0, 0, 1));
    for (int i = 1; i < rings; ++i) {
        const double theta = pi * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2.0 * pi * j / segments;
            const Vec3d n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                          std::cos(theta));
            mesh.positions.push_back((radius * n).cast<float>());
            mesh.normals.push_back(n.cast<float>());
        }
    }
    mesh.positions.push_back(Vec3f(0, 0, static_cast<float>(-radius)));
    mesh.normals.push_back(Vec3f(0, 0, -1));
    const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
    auto at = [&](int ring, int seg) {
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
    return mesh;
}

Mesh make_corrugated_strip(int nx, int ny, double half_x, double half_y, double amplitude,
                           double wavelength) {
    Mesh mesh;
    const double k = 2.0 * std::numbers::pi / wavelength;
    for (int j = 0; j <= ny; ++j) {
        for (int i = 0; i <= nx; ++i) {
            const double x = -half_x + 2.0 * half_x * i / nx;
            const double y = -half_y + 2.0 * half_y * j / ny;
            const double z = amplitude * std::sin(k * x);
            mesh.positions.push_back(Vec3d(x, y, z).cast<float>());
            mesh.normals.push_back(
                Vec3d(-amplitude * k * std::cos(k * x), 0.0, 1.0).normalized().cast<float>());
        }
    }
    auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            if ((i + j) % 2 == 0) {
                mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
            } else {
                mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
                mesh.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
            }
        }
    }
    return mesh;
}

Mesh make_corrugated_plane(int n, double half, double amplitude, double wavelength) {
    return make_corrugated_strip(n, n, half, half, amplitude, wavelength);
}

Mesh make_bumpy_sphere(int level) {
    Mesh mesh = make_icosphere(level, 1.0);
    for (auto& p : mesh.positions) {
        const Vec3d d = p.cast<double>().normalized();
        const double theta = std::acos(std::clamp(d.z(), -1.0, 1.0));
        const double phi = std::atan2(d.y(), d.x());
        p = ((1.0 + 0.15 * std::sin(5.0 * theta) * std::cos(3.0 * phi)) * d).cast<float>();
    }
    compute_vertex_normals(mesh);
    return mesh;
}

}  // namespace glint::test
