// The benchmarks' analytic blob pair (issue 13): an asymmetric ellipsoid-like blob (semi-axes
// 12 × 8 × 6 mm with two bumps), the reference tessellated as a latitude/longitude grid, the
// examined as a geodesic icosphere (each icosahedron face cut into f² triangles) — two
// tessellations of one surface whose vertices never coincide — with a dent 1 % of the size deep
// and 5 % wide, misaligned by 5° and 2 % of the size.
//
//   size class 1: reference uv 224 rings (199,808 triangles), examined f = 100 (200,000)
//   size class 2: reference uv 707 rings (1,996,568 triangles), examined f = 316 (1,997,120)
//
// note: the subdivided icosahedron of the phantoms has 20·4^level triangles (327,680 or
// 1,310,720 near the two sizes); the geodesic frequency f reaches any size.
#pragma once

#include "mesh/damage.h"
#include "mesh/normals.h"
#include "mesh/phantom.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>

namespace glint::bench {

inline constexpr double kBlobSize = 24.0;  // mm, the blob's largest dimension
inline const Vec3d kBlobRadii{12.0, 8.0, 6.0};

/// The unit geodesic sphere of frequency f (20·f² triangles, outward winding).
inline Mesh geodesic_sphere(int f) {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    const double c[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                             {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                             {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    const std::uint32_t faces[20][3] = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    Mesh m;
    // A lattice point is keyed by its corners and weights in canonical (sorted) order, so the
    // points on an edge shared by two faces get one vertex and one position.
    std::unordered_map<std::uint64_t, std::uint32_t> ids;
    const auto vertex = [&](const std::uint32_t corner[3], int i, int j) {
        std::array<std::pair<std::uint32_t, int>, 3> w{
            {{corner[0], f - i - j}, {corner[1], i}, {corner[2], j}}};
        // Zero weights first (their corner differs between the faces sharing an edge).
        std::sort(w.begin(), w.end(), [](const auto& x, const auto& y) {
            return std::pair(x.second != 0, x.first) < std::pair(y.second != 0, y.first);
        });
        std::uint64_t key = 0;
        Vec3d p = Vec3d::Zero();
        for (const auto& [k, weight] : w) {
            key =
                (key << 21) |
                (weight == 0 ? 0u : (std::uint64_t{k} << 16 | static_cast<std::uint64_t>(weight)));
            p += weight * Vec3d(c[k][0], c[k][1], c[k][2]);
        }
        const auto [it, fresh] =
            ids.try_emplace(key, static_cast<std::uint32_t>(m.positions.size()));
        if (fresh) m.positions.push_back(p.normalized().cast<float>());
        return it->second;
    };
    for (const auto& face : faces)
        for (int i = 0; i < f; ++i)
            for (int j = 0; i + j < f; ++j) {
                const std::uint32_t a = vertex(face, i, j), b = vertex(face, i + 1, j),
                                    d = vertex(face, i, j + 1);
                m.triangles.push_back({a, b, d});
                if (i + j + 1 < f) m.triangles.push_back({b, vertex(face, i + 1, j + 1), d});
            }
    return m;
}

/// The blob's two bumps (both meshes carry them: they are shape, not damage).
inline void add_blob_bumps(Mesh& m) {
    apply_damage(
        m,
        {DamageSpec{.kind = DamageKind::Bump, .center = {6.9, 4.0, 3.3}, .radius = 4, .depth = 1.5},
         DamageSpec{
             .kind = DamageKind::Bump, .center = {-9.0, 0.0, -3.9}, .radius = 3, .depth = 1.0}});
    m.labels.clear();
    m.scalars.clear();
}

/// The reference: the uv phantom ellipsoid with the bumps.
inline Mesh blob_reference(int rings) {
    Mesh m = make_phantom({.kind = PhantomKind::Ellipsoid,
                           .scheme = TessellationScheme::Uv,
                           .resolution = rings,
                           .radii = kBlobRadii});
    add_blob_bumps(m);
    return m;
}

/// The same blob on the geodesic sphere of frequency f, mapped radially onto the ellipsoid as
/// the phantoms are.
inline Mesh blob_geodesic(int f) {
    Mesh m = geodesic_sphere(f);
    for (auto& p : m.positions) {
        const Vec3d d = p.cast<double>();
        p = (d / (d.array() / kBlobRadii.array()).matrix().norm()).cast<float>();
    }
    m.unit = "mm";
    compute_vertex_normals(m);
    add_blob_bumps(m);
    return m;
}

struct BlobPair {
    Mesh reference;
    Mesh examined;  ///< damaged and moved: truth.inverse() applied
    Rigid truth;    ///< reference_from_examined
};

/// The pair of a size class (1: ~200k triangles each, 2: ~2M each; file comment).
inline BlobPair make_blob_pair(int size_class) {
    const bool big = size_class == 2;
    BlobPair p;
    p.reference = blob_reference(big ? 707 : 224);
    p.examined = blob_geodesic(big ? 316 : 100);
    apply_damage(p.examined, {DamageSpec{.kind = DamageKind::Dent,
                                         .center = {0, -8, 0},
                                         .radius = 0.05 * kBlobSize,
                                         .depth = 0.01 * kBlobSize}});
    p.examined.labels.clear();
    p.examined.scalars.clear();
    p.truth = Rigid::Identity();
    p.truth.linear() = Eigen::AngleAxisd(5.0 * std::numbers::pi / 180, Vec3d(1, 2, 3).normalized())
                           .toRotationMatrix();
    p.truth.translation() = Vec3d(0.02 * kBlobSize, 0, 0);
    transform_mesh(p.examined, p.truth.inverse());
    return p;
}

}  // namespace glint::bench
