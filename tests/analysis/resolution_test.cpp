// Surfaces closer than the scans resolve (analysis/resolution.h): thin plates, a thin
// process's tip and narrow gaps are flagged on a coarse grid and not on a fine one; thick parts never; mesh files carry no
// grid and nothing is flagged.
#include "analysis/resolution.h"

#include "mesh/geometry.h"
#include "volume/phantom.h"
#include "volume/surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

namespace glint {
namespace {

Mesh ellipsoid_surface(const Vec3d& center, const Vec3d& radii, double spacing) {
    EllipsoidVolumeOptions o;
    o.center = center;
    o.radii = radii;
    o.grid.spacing = Vec3d::Constant(spacing);
    const Vec3d half = radii + Vec3d::Constant(3.0);
    for (int d = 0; d < 3; ++d)
        o.grid.size[static_cast<std::size_t>(d)] =
            static_cast<std::size_t>(2 * half[d] / spacing) + 1;
    o.grid.origin = center - half;
    return extract_surface(make_ellipsoid_volume(o), {.iso = 500.0}).mesh;
}

Mesh merged(const Mesh& a, const Mesh& b) {
    Mesh m = a;
    const auto base = static_cast<std::uint32_t>(a.vertex_count());
    m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
    m.normals.insert(m.normals.end(), b.normals.begin(), b.normals.end());
    for (auto t : b.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    return m;
}

Eigen::Matrix3d grid(double x, double y, double z) { return Vec3d(x, y, z).asDiagonal(); }

ResolutionEvidence flag(const Mesh& reference, const Mesh& examined,
                        std::optional<double> given = std::nullopt) {
    return below_resolution(reference, examined, resolution_grids(reference, examined, given),
                            nullptr, nullptr);
}

// Share of the vertices selected by `pick` that are flagged.
template <class Pick>
double flagged_share(const Mesh& m, const ResolutionEvidence& e, Pick pick) {
    std::size_t n = 0, f = 0;
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
        if (pick(m.positions[v].cast<double>(), m.normals[v].cast<double>())) {
            ++n;
            f += e.below[v];
        }
    EXPECT_GT(n, 20u);
    return n ? static_cast<double>(f) / static_cast<double>(n) : 0.0;
}

TEST(Resolution, VoxelExtentIsTheVoxelsWidthAlongTheDirection) {
    const Eigen::Matrix3d a = grid(1, 1, 2);
    EXPECT_DOUBLE_EQ(voxel_extent_along(a, {0, 0, 1}), 2.0);
    EXPECT_DOUBLE_EQ(voxel_extent_along(a, {1, 0, 0}), 1.0);
    EXPECT_NEAR(voxel_extent_along(a, Vec3d(1, 1, 1).normalized()), 4.0 / std::sqrt(3.0), 1e-12);
    // A turned grid: the same voxel seen along its own axis is its spacing there.
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(0.7, Vec3d(1, 2, 3).normalized()).toRotationMatrix();
    EXPECT_NEAR(voxel_extent_along(r * a, r * Vec3d(0, 0, 1)), 2.0, 1e-12);
}

// The staircase steps by the axis the normal leans on most: the slice thickness where a face
// lies along the slices, less where it crosses the grid diagonally (where the voxel's width
// along the normal is largest instead): CThead's erosion and a vault terrace.
TEST(Resolution, StaircaseStepIsTheAxisTheNormalLeansOnMost) {
    const Eigen::Matrix3d a = grid(1, 1, 2);
    EXPECT_DOUBLE_EQ(staircase_step(a, {0, 0, 1}), 2.0);
    EXPECT_DOUBLE_EQ(staircase_step(a, {1, 0, 0}), 1.0);
    const Vec3d erosion = Vec3d(-0.56, -0.68, -0.46).normalized();
    const Vec3d terrace = Vec3d(0.1, 0.1, 0.99).normalized();
    EXPECT_NEAR(staircase_step(a, erosion), 2 * 0.46 / Vec3d(-0.56, -0.68, -0.46).norm(), 1e-12);
    EXPECT_GT(staircase_step(a, terrace), 1.9);
    EXPECT_LT(staircase_step(a, erosion), 1.0);
    // The voxel's width cannot tell the two apart: both about 2.1 mm.
    EXPECT_NEAR(voxel_extent_along(a, erosion), voxel_extent_along(a, terrace), 0.1);
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(0.7, Vec3d(1, 2, 3).normalized()).toRotationMatrix();
    EXPECT_NEAR(staircase_step(r * a, r * terrace), staircase_step(a, terrace), 1e-12);
}

TEST(Resolution, ExtractedSurfacesCarryTheirGridAndMotionsTurnIt) {
    Mesh m = ellipsoid_surface({0, 0, 0}, {5, 5, 5}, 0.5);
    ASSERT_TRUE(m.voxel_axes.has_value());
    EXPECT_TRUE(m.voxel_axes->isApprox(grid(0.5, 0.5, 0.5)));
    Rigid t = Rigid::Identity();
    t.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3d::UnitX()).toRotationMatrix();
    m.voxel_axes = grid(1, 1, 2);
    transform_mesh(m, t);
    EXPECT_TRUE(m.voxel_axes->col(2).isApprox(Vec3d(0, -2, 0), 1e-12));
}

TEST(Resolution, AThinPlateIsBelowACoarseGridAndResolvedByAFineOne) {
    // A plate 1.4 mm thick: across it a 1 × 1 × 2 mm voxel (2 mm along z) holds both faces,
    // a 0.25 mm voxel does not.
    Mesh plate = ellipsoid_surface({0, 0, 0}, {12, 12, 0.7}, 0.25);
    const auto faces = [](const Vec3d& p, const Vec3d& n) {
        return std::abs(n.z()) > 0.9 && p.head<2>().norm() < 6.0;
    };
    const ResolutionEvidence fine = flag(plate, plate);
    ASSERT_EQ(fine.below.size(), plate.vertex_count());
    EXPECT_EQ(flagged_share(plate, fine, faces), 0.0);
    for (const float c : fine.clearance) ASSERT_FALSE(std::isnan(c));
    plate.voxel_axes = grid(1, 1, 2);
    const ResolutionEvidence coarse = flag(plate, plate);
    EXPECT_GT(flagged_share(plate, coarse, faces), 0.95);
    EXPECT_GT(coarse.flagged_area, 0.0);
    EXPECT_NE(coarse.rule.find("1 × 1 × 2"), std::string::npos) << coarse.rule;
    // A thick body on the same coarse grid: nothing.
    Mesh ball = ellipsoid_surface({0, 0, 0}, {8, 8, 8}, 0.5);
    ball.voxel_axes = grid(1, 1, 2);
    const ResolutionEvidence thick = flag(ball, ball);
    EXPECT_EQ(flagged_share(ball, thick, [](const Vec3d&, const Vec3d&) { return true; }), 0.0);
}

TEST(Resolution, AThinProcesssTipIsBelowResolutionThoughItsNormalRunsAlongIt) {
    // A process 3 mm across and 8 mm long along the 2 mm slices: along its tip's normal the
    // far side is 8 mm away (4 voxels), but 45° off the axis the process's flank lies within
    // 1.4 mm, under the voxel's 2.1–2.4 mm seen that way: partial volume decides how far the
    // tip reaches.
    Mesh process = ellipsoid_surface({0, 0, 0}, {1.5, 1.5, 4.0}, 0.08);
    process.voxel_axes = grid(1, 1, 2);
    const auto tip = [](const Vec3d& p, const Vec3d& n) { return p.z() > 3.0 && n.z() > 0.9; };
    const ResolutionEvidence e = flag(process, process);
    EXPECT_EQ(flagged_share(process, e, tip), 1.0);
    for (std::size_t v = 0; v < process.vertex_count(); ++v) {
        if (!tip(process.positions[v].cast<double>(), process.normals[v].cast<double>())) continue;
        EXPECT_GT(e.clearance[v], 2.0 * 2.0) << "the normal alone would not flag the tip";
    }
    EXPECT_NE(e.rule.find("tilted 45°"), std::string::npos) << e.rule;
    // A blunt end of the same grid, a ball 6 mm across: its chords 45° off the normal are
    // 4.2 mm long, nearly two voxels, and nothing is flagged.
    Mesh ball = ellipsoid_surface({0, 0, 0}, {3, 3, 3}, 0.25);
    ball.voxel_axes = grid(1, 1, 2);
    EXPECT_EQ(
        flagged_share(ball, flag(ball, ball), [](const Vec3d&, const Vec3d&) { return true; }),
        0.0);
    // The same process on a grid eight times finer is resolved at its tip.
    process.voxel_axes = grid(0.125, 0.125, 0.25);
    EXPECT_EQ(flagged_share(process, flag(process, process), tip), 0.0);
}

TEST(Resolution, AGapOnlyTheExaminedScanHasIsFlaggedOnItsSideOnly) {
    // Two balls 0.6 mm apart in the examined scan, one of them in the reference: the
    // reference's side facing the gap is below a 1 mm grid, its far side is not.
    const Mesh ball = ellipsoid_surface({0, 0, 0}, {6, 6, 6}, 0.5);
    const Mesh other = ellipsoid_surface({12.6, 0, 0}, {6, 6, 6}, 0.5);
    Mesh reference = ball;
    Mesh examined = merged(ball, other);
    reference.voxel_axes = grid(1, 1, 1);
    examined.voxel_axes = grid(1, 1, 1);
    const ResolutionEvidence e = flag(reference, examined);
    // (vertices whose normal faces outwards: marching cubes leaves a few degenerate ones)
    const auto facing = [](const Vec3d& p, const Vec3d& n) { return n.dot(p.normalized()) > 0.5; };
    EXPECT_EQ(
        flagged_share(reference, e,
                      [&](const Vec3d& p, const Vec3d& n) { return p.x() > 5.8 && facing(p, n); }),
        1.0);
    EXPECT_EQ(flagged_share(reference, e, [](const Vec3d& p, const Vec3d&) { return p.x() < 3.0; }),
              0.0);
    // The grid of one scan is enough; mesh files (no grid on either) flag nothing.
    reference.voxel_axes.reset();
    EXPECT_EQ(flag(reference, examined).below.size(), reference.vertex_count());
    examined.voxel_axes.reset();
    const ResolutionEvidence none = flag(reference, examined);
    EXPECT_TRUE(none.below.empty());
    EXPECT_TRUE(none.rule.empty());
}

// A hollow ball: outer radius `outer`, a cavity of radius `inner`, on a 0.25 mm grid.
Mesh shell_surface(double outer, double inner) {
    EllipsoidVolumeOptions o;
    o.radii = Vec3d::Constant(outer);
    o.grid.spacing = Vec3d::Constant(0.25);
    const double half = outer + 3.0;
    for (auto& size : o.grid.size) size = static_cast<std::size_t>(2 * half / 0.25) + 1;
    o.grid.origin = Vec3d::Constant(-half);
    Volume v = make_ellipsoid_volume(o);
    o.radii = Vec3d::Constant(inner);
    const Volume cavity = make_ellipsoid_volume(o);
    for (std::size_t i = 0; i < v.voxels.size(); ++i) v.voxels[i] -= cavity.voxels[i];
    return extract_surface(v, {.iso = 500.0}).mesh;
}

TEST(Resolution, BoneThinnedByALossFartherThanAVoxelStaysCompared) {
    // The reference a solid ball of radius 6 on a 1 mm grid. Examined: a shell 0.6 mm thick,
    // under the voxel. Where the shell's outer face is the reference's own (radius 6), its
    // thinness decides where each scan puts the surface: flagged. Where it lies 1.9 mm inside
    // (radius 4.1, the bone eroded down to a thin layer), farther than the voxel is wide along
    // any normal (√3 mm on the diagonal), the loss is larger than partial volume can move a
    // surface: compared.
    Mesh reference = ellipsoid_surface({0, 0, 0}, {6, 6, 6}, 0.25);
    reference.voxel_axes = grid(1, 1, 1);
    const auto outer = [](const Vec3d& p, const Vec3d& n) { return n.dot(p.normalized()) > 0.9; };
    Mesh thin_in_place = shell_surface(6.0, 5.4);
    thin_in_place.voxel_axes = grid(1, 1, 1);
    EXPECT_GT(flagged_share(reference, flag(reference, thin_in_place), outer), 0.95);
    Mesh eroded = shell_surface(4.1, 3.5);
    eroded.voxel_axes = grid(1, 1, 1);
    EXPECT_EQ(flagged_share(reference, flag(reference, eroded), outer), 0.0);
    // Gone 0.8 mm deep (under a voxel) to a thin layer: partial volume could place it.
    Mesh shallow = shell_surface(5.2, 4.6);
    shallow.voxel_axes = grid(1, 1, 1);
    EXPECT_GT(flagged_share(reference, flag(reference, shallow), outer), 0.95);
}

TEST(Resolution, AMeshFileTakesTheGivenResolutionAndAVolumesGridWins) {
    // The plate as a mesh file would hold it (no grid): off, unless --resolution says 2 mm.
    Mesh plate = ellipsoid_surface({0, 0, 0}, {12, 12, 0.7}, 0.25);
    plate.voxel_axes.reset();
    const auto faces = [](const Vec3d& p, const Vec3d& n) {
        return std::abs(n.z()) > 0.9 && p.head<2>().norm() < 6.0;
    };
    EXPECT_TRUE(flag(plate, plate).below.empty());
    const ResolutionGrids g = resolution_grids(plate, plate, 2.0);
    ASSERT_TRUE(g.reference && g.examined);
    EXPECT_TRUE(g.given);
    EXPECT_TRUE(g.reference->isApprox(grid(2, 2, 2)));
    const ResolutionEvidence given = flag(plate, plate, 2.0);
    EXPECT_GT(flagged_share(plate, given, faces), 0.95);
    EXPECT_NE(given.rule.find("--resolution"), std::string::npos) << given.rule;
    // A surface from a volume keeps its own grid: 0.25 mm resolves the 1.4 mm plate.
    Mesh from_volume = plate;
    from_volume.voxel_axes = grid(0.25, 0.25, 0.25);
    const ResolutionGrids own = resolution_grids(from_volume, from_volume, 2.0);
    EXPECT_FALSE(own.given);
    EXPECT_EQ(flagged_share(from_volume, flag(from_volume, from_volume, 2.0), faces), 0.0);
}

}  // namespace
}  // namespace glint
