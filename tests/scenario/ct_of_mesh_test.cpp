// A CT scan of a solid given as a closed mesh (scenario/ct_of_mesh.h): partial volume holds the
// solid's volume, the iso-surface at the middle value lies on the mesh, the motion moves the
// solid, the erosion removes what its ball holds, cavities stay empty and a surface wound
// inside out images the same solid.
#include "scenario/ct_of_mesh.h"

#include "mesh/error.h"
#include "mesh/phantom.h"
#include "volume/surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

Mesh sphere(double radius) {
    PhantomOptions o;
    o.radii = Vec3d::Constant(radius);
    o.resolution = 5;
    return make_phantom(o);
}

// The solid the scan holds, mm³: each voxel's share of material times its volume.
double material(const Volume& v, const MeshScan& scan) {
    double sum = 0.0;
    for (float x : v.voxels) sum += (x - scan.background) / (scan.object - scan.background);
    return sum * v.geometry.spacing.prod();
}

Vec3d material_centroid(const Volume& v, const MeshScan& scan) {
    Vec3d c = Vec3d::Zero();
    double w = 0.0;
    const auto& n = v.geometry.size;
    for (std::size_t k = 0; k < n[2]; ++k)
        for (std::size_t j = 0; j < n[1]; ++j)
            for (std::size_t i = 0; i < n[0]; ++i) {
                const double f = (v.voxels[v.geometry.offset(i, j, k)] - scan.background) /
                                 (scan.object - scan.background);
                c += f * v.geometry.physical_from_index(Vec3d(double(i), double(j), double(k)));
                w += f;
            }
    return c / w;
}

TEST(ScanMesh, PartialVolumeHoldsTheSolidAndItsIsoSurfaceLiesOnTheMesh) {
    MeshScan scan;
    scan.voxel_size = {0.5, 0.5, 0.5};
    const Mesh object = sphere(5.0);
    const Volume v = scan_mesh(object, scan);
    // The phantom's polyhedron is a little smaller than the ball it approximates.
    double polyhedron = 0.0;
    for (const auto& t : object.triangles)
        polyhedron +=
            object.positions[t[0]].cast<double>().dot(object.positions[t[1]].cast<double>().cross(
                object.positions[t[2]].cast<double>())) /
            6.0;
    EXPECT_NEAR(material(v, scan), polyhedron, 0.005 * polyhedron);
    // A grid over the solid and its margin: four voxels beyond the box on each side.
    EXPECT_NEAR(v.geometry.origin.x(), -7.0, 1e-9);
    EXPECT_EQ(v.geometry.spacing, Vec3d(0.5, 0.5, 0.5));
    const Mesh surface = extract_surface(v, {.iso = 0.5 * (1040.0 + 1800.0)}).mesh;
    double worst = 0.0;
    for (const auto& p : surface.positions)
        worst = std::max(worst, std::abs(p.cast<double>().norm() - 5.0));
    EXPECT_LT(worst, 0.08);  // a sixth of a voxel
}

TEST(ScanMesh, TheMotionMovesTheSolidAndTheErosionRemovesWhatItsBallHolds) {
    MeshScan scan;
    scan.voxel_size = {0.4, 0.4, 0.4};
    const Mesh object = sphere(5.0);
    const double whole = material(scan_mesh(object, scan), scan);
    scan.moved_from_original = Rigid(Eigen::Translation3d(2.0, -1.0, 0.5));
    const Volume moved = scan_mesh(object, scan);
    EXPECT_LT((material_centroid(moved, scan) - Vec3d(2.0, -1.0, 0.5)).norm(), 0.01);
    EXPECT_NEAR(material(moved, scan), whole, 0.002 * whole);
    // A ball of radius 2 centred on the surface at +z (before the motion) takes the lens the
    // two balls share: π (R + r − d)² (d² + 2dr − 3r² + 2dR + 6rR − 3R²) / (12 d), d = R.
    scan.erosions = {{Vec3d(0, 0, 5), 2.0, 1040.0f}};
    const Volume eroded = scan_mesh(object, scan);
    const double R = 5, r = 2, d = 5;
    const double lens = std::numbers::pi * std::pow(R + r - d, 2) *
                        (d * d + 2 * d * r - 3 * r * r + 2 * d * R + 6 * r * R - 3 * R * R) /
                        (12 * d);
    EXPECT_NEAR(whole - material(eroded, scan), lens, 0.05 * lens);
    // Eroded where the ball went with the solid: the top moved, not the bottom.
    const auto& g = eroded.geometry;
    const Vec3d top = g.index_from_physical(Vec3d(2.0, -1.0, 0.5 + 4.0));
    const Vec3d bottom = g.index_from_physical(Vec3d(2.0, -1.0, 0.5 - 4.0));
    auto at = [&](const Volume& v, const Vec3d& i) {
        return v.voxels[g.offset(std::size_t(std::lround(i.x())), std::size_t(std::lround(i.y())),
                                 std::size_t(std::lround(i.z())))];
    };
    EXPECT_FLOAT_EQ(at(eroded, top), 1040.0f);
    EXPECT_FLOAT_EQ(at(eroded, bottom), 1800.0f);
}

TEST(ScanMesh, ACavityStaysEmptyAndASurfaceWoundInsideOutImagesTheSameSolid) {
    // A shell: a sphere of radius 5 with a cavity of radius 3 (its surface wound inwards).
    Mesh shell = sphere(5.0);
    Mesh inner = sphere(3.0);
    const auto base = static_cast<std::uint32_t>(shell.vertex_count());
    for (const auto& p : inner.positions) shell.positions.push_back(p);
    for (auto t : inner.triangles)
        shell.triangles.push_back({t[0] + base, t[2] + base, t[1] + base});
    shell.normals.clear();
    MeshScan scan;
    scan.voxel_size = {0.4, 0.4, 0.4};
    const double volume = material(scan_mesh(shell, scan), scan);
    const double expected = 4.0 / 3.0 * std::numbers::pi * (125.0 - 27.0);
    EXPECT_NEAR(volume, expected, 0.02 * expected);
    Mesh turned = sphere(5.0);
    for (auto& t : turned.triangles) std::swap(t[1], t[2]);
    turned.normals.clear();
    const Mesh plain = sphere(5.0);
    EXPECT_NEAR(material(scan_mesh(turned, scan), scan), material(scan_mesh(plain, scan), scan),
                1e-6);
}

TEST(ScanMesh, TheScannersBlurAndNoiseComeLast) {
    MeshScan scan;
    scan.voxel_size = {0.5, 0.5, 0.5};
    scan.scanner = {
        .psf_fwhm = 0.6, .noise_sigma = 30.0, .noise_correlation = 0.3, .noise_seed = 3};
    const Volume v = scan_mesh(sphere(4.0), scan);
    // The centre voxel holds bone plus noise; the margin grew by three σ of each.
    const Vec3d c = v.geometry.index_from_physical(Vec3d::Zero());
    const float centre =
        v.voxels[v.geometry.offset(std::size_t(std::lround(c.x())), std::size_t(std::lround(c.y())),
                                   std::size_t(std::lround(c.z())))];
    EXPECT_NEAR(centre, 1800.0f, 5 * 30.0f);
    EXPECT_NE(centre, 1800.0f);
    EXPECT_LT(v.geometry.origin.x(), -4.0 - 2.0 - 3 * (0.2548 + 0.3) + 0.5);
}

TEST(ScanMesh, RefusesAnEmptyMeshAVoxelThatIsNoSizeAndValuesThatCannotTellTheSolid) {
    MeshScan scan;
    EXPECT_THROW((void)scan_mesh(Mesh{}, scan), InputError);
    const Mesh object = sphere(2.0);
    scan.voxel_size = {0.4, 0.0, 0.4};
    EXPECT_THROW((void)scan_mesh(object, scan), InputError);
    scan.voxel_size = {0.4, 0.4, 0.4};
    scan.object = scan.background;
    EXPECT_THROW((void)scan_mesh(object, scan), InputError);
    scan.object = 1800.0f;
    scan.erosions = {{Vec3d(NAN, 0, 0), 1.0, 1040.0f}};
    EXPECT_THROW((void)scan_mesh(object, scan), InputError);
    scan.erosions.clear();
    scan.voxel_size = {1e-4, 1e-4, 1e-4};  // 4 · 10¹⁰ voxels: over the budget, refused first
    try {
        (void)scan_mesh(object, scan);
        FAIL() << "expected the voxel budget to refuse";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("above the budget"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace glint
