#include "mesh/voxel_grid.h"
#include "mesh/geometry.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tuple>

namespace glint {
namespace {

// The vertices marching cubes places on an ellipsoid sampled on a grid of spacing `s` from
// `origin`: where a grid edge along one axis crosses the surface, the other two coordinates
// are the edge's grid planes (as float, one expression per plane).
Mesh marching_cubes_vertices(const Eigen::Vector3d& s, const Eigen::Vector3d& origin,
                             const Eigen::Vector3d& radii) {
    Mesh m;
    const auto plane = [&](int k, int i) { return static_cast<float>(origin[k] + i * s[k]); };
    const int reach[3] = {static_cast<int>(std::ceil(radii[0] / s[0])) + 2,
                          static_cast<int>(std::ceil(radii[1] / s[1])) + 2,
                          static_cast<int>(std::ceil(radii[2] / s[2])) + 2};
    for (int along = 0; along < 3; ++along) {
        const int a = (along + 1) % 3, b = (along + 2) % 3;
        for (int i = -reach[a]; i <= reach[a]; ++i)
            for (int j = -reach[b]; j <= reach[b]; ++j) {
                const double u = plane(a, i) / radii[a], w = plane(b, j) / radii[b];
                const double rest = 1.0 - u * u - w * w;
                if (rest <= 0) continue;
                for (const double sign : {-1.0, 1.0}) {
                    Vec3f p;
                    p[a] = plane(a, i);
                    p[b] = plane(b, j);
                    p[along] = static_cast<float>(sign * radii[along] * std::sqrt(rest));
                    m.positions.push_back(p);
                }
            }
    }
    return m;
}

TEST(VoxelGrid, FindsTheAnisotropicGridOfMarchingCubesVertices) {
    const Eigen::Vector3d spacing(0.4, 0.7, 1.2);
    const Mesh m = marching_cubes_vertices(spacing, {0.13, -0.21, 0.05}, {20, 15, 25});
    const auto g = detect_voxel_grid(m);
    ASSERT_TRUE(g.has_value());
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(g->spacing[k], spacing[k], 1e-4) << "axis " << k;
    EXPECT_GT(g->on_edges, 0.9);
}

TEST(VoxelGrid, FindsNoGridOnAMeshTurnedAfterExtraction) {
    // Turned after extraction: the planes are no longer along the axes. (A smoothed export,
    // whose vertices left the grid's edges, keeps its grid's period: tests/volume/surface_test.)
    Mesh turned = marching_cubes_vertices({0.5, 0.5, 0.5}, {0, 0, 0}, {20, 15, 25});
    transform_mesh(turned, Rigid(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())));
    EXPECT_FALSE(detect_voxel_grid(turned).has_value());
}

TEST(VoxelGrid, FindsNoGridOnMeshesThatAreNotMarchingCubesOutput) {
    // A structured grid's vertices lie on planes in all three coordinates, not two.
    Mesh lattice;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j)
            for (int k = 0; k < 10; ++k)
                lattice.positions.push_back(
                    Vec3f(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) *
                    0.5f);
    EXPECT_FALSE(detect_voxel_grid(lattice).has_value());
    // A UV sphere repeats its ring heights, not its x or y.
    PhantomOptions o;
    o.kind = PhantomKind::Sphere;
    o.scheme = TessellationScheme::Uv;
    o.resolution = 64;
    EXPECT_FALSE(detect_voxel_grid(make_phantom(o)).has_value());
    o.scheme = TessellationScheme::Ico;
    o.resolution = 5;
    EXPECT_FALSE(detect_voxel_grid(make_phantom(o)).has_value());
    EXPECT_FALSE(detect_voxel_grid(Mesh{}).has_value());
    // Nor a lattice of periods: the tessellations' own rings and the condyle's shape are not
    // one grid through the whole surface (lattice_of_vertices, read with their triangles).
    for (const auto& [kind, scheme, resolution] :
         {std::tuple{PhantomKind::Sphere, TessellationScheme::Uv, 256},
          std::tuple{PhantomKind::Sphere, TessellationScheme::Ico, 6},
          std::tuple{PhantomKind::Condyle, TessellationScheme::Ico, 6},
          std::tuple{PhantomKind::Ellipsoid, TessellationScheme::Uv, 256}}) {
        o.kind = kind;
        o.scheme = scheme;
        o.resolution = resolution;
        const Mesh m = make_phantom(o);
        ASSERT_GT(m.triangle_count(), 20000u);
        EXPECT_FALSE(lattice_of_vertices(m).has_value()) << static_cast<int>(kind);
    }
}

// An open tube along z from 0 to `length`: its two rims are open borders on its box's z faces.
Mesh open_tube(double length) {
    Mesh m;
    const int around = 24, along = 10;
    for (int j = 0; j <= along; ++j)
        for (int i = 0; i < around; ++i) {
            const double a = 2.0 * 3.14159265358979 * i / around;
            m.positions.push_back(Vec3f(static_cast<float>(5.0 * std::cos(a)),
                                        static_cast<float>(5.0 * std::sin(a)),
                                        static_cast<float>(length * j / along)));
        }
    for (int j = 0; j < along; ++j)
        for (int i = 0; i < around; ++i) {
            const auto at = [&](int jj, int ii) {
                return static_cast<std::uint32_t>(jj * around + (ii % around));
            };
            m.triangles.push_back({at(j, i), at(j, i + 1), at(j + 1, i + 1)});
            m.triangles.push_back({at(j, i), at(j + 1, i + 1), at(j + 1, i)});
        }
    return m;
}

TEST(VoxelGrid, AVolumeEdgeThatCutTheSurfaceBoundsItsFieldOfView) {
    DetectedGrid g;
    g.spacing = {0.5, 0.5, 2.0};
    const FieldOfView fov = field_of_view_of_cut(open_tube(10.0), g);
    ASSERT_EQ(fov.boxes.size(), 1u);
    // Beyond either rim's plane: outside; beside the tube, however far: inside.
    EXPECT_LT(fov.depth_inside({0, 0, 11}), 0.0);
    EXPECT_LT(fov.depth_inside({0, 0, -1}), 0.0);
    EXPECT_GT(fov.depth_inside({0, 0, 5}), 4.0);
    EXPECT_GT(fov.depth_inside({300, -300, 5}), 4.0);
    // A closed surface was cut nowhere: its field of view stays unknown.
    PhantomOptions o;
    EXPECT_TRUE(field_of_view_of_cut(make_phantom(o), g).empty());
}

}  // namespace
}  // namespace glint
