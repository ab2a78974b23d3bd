// One-scan asymmetry (analysis/asymmetry.h): the surface against its own mirror image through
// the regular pipeline. A procedural shape with one mirror plane for speed; the real jaw
// (jaw_smooth.obj, mirror-symmetric in x) re-tessellated and moved, clean and with one-sided
// damage on its right (+x) condyle made as the real-pair generator makes it (mesh/damage.h).
#include "analysis/asymmetry.h"

#include "mesh/damage.h"
#include "mesh/geometry.h"
#include "mesh/io.h"
#include "mesh/normals.h"
#include "mesh/phantom.h"
#include "mesh/remesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path kJaw =
    fs::path(GLINT_SHARED_DATA_DIR) / "mandible_cbct_artisynth" / "jaw_smooth.obj";

// The right condyle's top (scenarios/data/pair_jaw_condyle_dent.toml).
const Vec3d kRightCondyle{55.1, 31.5, 84.1};

Rigid motion(double deg, const Vec3d& axis, const Vec3d& t) {
    Rigid r = Rigid::Identity();
    r.linear() = Eigen::AngleAxisd(deg * std::numbers::pi / 180.0, axis.normalized()).matrix();
    r.translation() = t;
    return r;
}

AnalysisOptions sweep_options() {
    AnalysisOptions o;
    o.sweep.render.backend = Backend::Embree;
    return o;
}

struct MirrorRun {
    AsymmetryPlane plane;
    AnalysisResult analysis;
    AsymmetryFindings findings;
};

MirrorRun run_asymmetry(const Mesh& mesh) {
    MirrorRun r;
    r.plane = prepare_asymmetry(mesh, {});
    EXPECT_TRUE(r.plane.plane.plausible) << r.plane.plane.verdict;
    if (r.plane.mirror.triangles.empty()) return r;
    r.analysis = analyse(mesh, r.plane.mirror, sweep_options());
    r.findings = pair_findings(mesh, r.plane.plane.plane, r.analysis);
    return r;
}

// The plane found, taken back through the motion, against x = 0 at `centre`.
void expect_near_x0(const SymmetryPlane& found, const Rigid& moved, const Vec3d& centre) {
    const Rigid back = moved.inverse();
    const SymmetryPlane p = plane_through(back * found.point(), back.linear() * found.normal);
    const double angle =
        std::acos(std::min(1.0, std::abs(p.normal.x()))) * 180.0 / std::numbers::pi;
    EXPECT_LT(angle, 0.2);
    EXPECT_LT(std::abs(p.distance(centre)), 0.1);
    std::printf("plane %.4f° and %.4f mm from x = 0\n", angle, std::abs(p.distance(centre)));
}

// F1 of a region's vertices against the generator's labels (mesh/damage.h).
double f1_of(const Mesh& mesh, const RegionResult& regions, std::int32_t region) {
    std::size_t tp = 0, fp = 0, fn = 0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const bool found = regions.region_of_vertex[v] == region;
        const bool truth = mesh.labels[v] > 0;
        tp += found && truth;
        fp += found && !truth;
        fn += !found && truth;
    }
    return tp == 0 ? 0.0 : 2.0 * double(tp) / double(2 * tp + fp + fn);
}

// An ellipsoid bent so that x = 0 is its only mirror plane.
Mesh one_plane_shape() {
    Mesh m = make_phantom({.kind = PhantomKind::Ellipsoid, .resolution = 5, .radii = {30, 18, 12}});
    for (auto& p : m.positions) {
        const float x = p.x(), z = p.z();
        p = Vec3f(x * (1.0f + 0.25f * z / 12.0f), p.y() + 0.01f * x * x, z);
    }
    compute_vertex_normals(m);
    return m;
}

TEST(Asymmetry, OneSidedDentOfAShapeIsOneFindingOnItsSide) {
    Mesh m = one_plane_shape();
    apply_damage(
        m, {DamageSpec{.kind = DamageKind::Dent, .center = {18, 8, 6}, .radius = 4, .depth = 0.6}});
    const MirrorRun r = run_asymmetry(m);
    ASSERT_EQ(r.findings.findings.size(), 1u);
    const AsymmetryFinding& f = r.findings.findings[0];
    EXPECT_GT(f.side.x(), 0.99) << "the dent is on +x";
    EXPECT_LT(f.depth, -0.3) << "+x has less than the mirrored -x";
    EXPECT_GT(f.mirror_region, 0) << "its mirror image is the other member of the pair";
    EXPECT_GT(f1_of(m, r.analysis.decisions[0].regions, f.region), 0.8);
    EXPECT_NE(describe(f, "+x side", "-x side", "mm").find("+x side: 0."), std::string::npos)
        << describe(f, "+x side", "-x side", "mm");
}

// Pairing alone, on regions made by hand: a bump of the mirror at +x (the surface has less
// there) and a dent of the mirror at its mirror image are one finding, shown at +x; a region
// where the mirror has no surface stands alone and has no depth.
TEST(Asymmetry, PairsOppositeRegionsAtMirrorImagesIntoOneFinding) {
    AnalysisResult r;
    r.distance = {0.3f, -0.3f, 0.0f, 0.01f};
    ZoomDecision d;
    d.regions.region_of_vertex = {1, 2, 3, 0};
    d.regions.regions = {
        Region{.id = 1,
               .area = 4,
               .peak_depth = 0.3,
               .volume = 1.0,
               .centroid = {5, 1, 0},
               .kind = RegionKind::Bump},
        Region{.id = 2,
               .area = 4,
               .peak_depth = -0.3,
               .volume = -1.0,
               .centroid = {-5.2, 1, 0},
               .kind = RegionKind::Dent},
        Region{.id = 3, .area = 2, .centroid = {0.5, 8, 3}, .kind = RegionKind::MissingSurface}};
    r.decisions.push_back(d);
    const AsymmetryFindings f = pair_findings(Mesh{}, parse_plane_spec("x=0"), r);
    ASSERT_EQ(f.findings.size(), 2u);
    EXPECT_EQ(f.findings[0].region, 1);
    EXPECT_EQ(f.findings[0].mirror_region, 2);
    EXPECT_EQ(f.findings[0].side, Vec3d::UnitX());
    EXPECT_DOUBLE_EQ(f.findings[0].depth, -0.3);
    EXPECT_DOUBLE_EQ(f.findings[0].volume, -1.0);
    EXPECT_TRUE(f.findings[1].mirror_missing);
    EXPECT_TRUE(std::isnan(f.findings[1].depth));
    EXPECT_NE(describe(f.findings[1], "+x side", "-x side", "mm").find("no mirrored -x side"),
              std::string::npos);
    EXPECT_FLOAT_EQ(f.field[0], -0.3f);    // the surface minus its mirror: less
    EXPECT_NEAR(f.floor.max, 0.01, 1e-6);  // only the vertex in no region
}

// A lone region (its mirror image made no region of its own) is weighed as a pair is, against
// the surface at its mirror image: on a smooth shape neither side bends clearly less evenly, so
// a region where this side has more is shown at its mirror image as less; a region whose own
// surface is rough stays where it is; a region where this side has less stays too.
TEST(Asymmetry, ALoneRegionIsWeighedAgainstTheSurfaceAtItsMirrorImage) {
    const Mesh smooth = one_plane_shape();
    // The region's centre: the surface's vertex nearest (18, 8, 6).
    Vec3d c = smooth.positions[0].cast<double>();
    for (const auto& p : smooth.positions)
        if ((p.cast<double>() - Vec3d(18, 8, 6)).norm() < (c - Vec3d(18, 8, 6)).norm())
            c = p.cast<double>();
    const auto lone = [&c](const Mesh& m, RegionKind kind, double peak) {
        AnalysisResult r;
        r.distance.assign(m.vertex_count(), 0.0f);
        ZoomDecision d;
        d.regions.region_of_vertex.assign(m.vertex_count(), 0);
        for (std::size_t v = 0; v < m.vertex_count(); ++v)
            if ((m.positions[v].cast<double>() - c).norm() < 4.0) d.regions.region_of_vertex[v] = 1;
        d.regions.regions = {Region{.id = 1,
                                    .area = 50,
                                    .peak_depth = peak,
                                    .volume = 10 * peak,
                                    .centroid = c,
                                    .kind = kind}};
        r.decisions.push_back(d);
        return pair_findings(m, parse_plane_spec("x=0"), r);
    };
    // The mirror lies inside the region (a dent of the mirror): this side has more there.
    AsymmetryFindings f = lone(smooth, RegionKind::Dent, -0.5);
    ASSERT_EQ(f.findings.size(), 1u);
    const AsymmetryFinding& moved = f.findings[0];
    EXPECT_TRUE(moved.at_mirror_image);
    EXPECT_FALSE(moved.side_by_shape) << moved.roughness << " vs " << moved.mirror_roughness;
    EXPECT_EQ(moved.side, -Vec3d::UnitX()) << "shown on the other side";
    EXPECT_EQ(moved.region, 1);
    EXPECT_DOUBLE_EQ(moved.depth, -0.5) << "less than the mirrored +x";
    EXPECT_DOUBLE_EQ(moved.volume, -5.0);
    EXPECT_LT(moved.centroid.x(), -17.0) << "the mirror image of the region's centroid";
    EXPECT_GT(moved.roughness, 0.0);
    EXPECT_GT(moved.mirror_roughness, 0.0);
    EXPECT_NE(describe(moved, "-x side", "+x side", "mm")
                  .find("-x side: 0.5 mm less than the mirrored +x side, area 50 mm², volume 5 "
                        "mm³ (found as region 1 on the +x side, the mirror image of this place; "
                        "this side has no region of its own)"),
              std::string::npos)
        << describe(moved, "-x side", "+x side", "mm");

    // The same region where this side has less stays where it is.
    f = lone(smooth, RegionKind::Bump, 0.5);
    ASSERT_EQ(f.findings.size(), 1u);
    EXPECT_FALSE(f.findings[0].at_mirror_image);
    EXPECT_EQ(f.findings[0].side, Vec3d::UnitX());
    EXPECT_DOUBLE_EQ(f.findings[0].depth, -0.5);

    // A region whose own surface turns its curvature over (a bump made there) is the changed
    // side by its shape: it stays, though it has more.
    Mesh rough = one_plane_shape();
    apply_damage(rough,
                 {DamageSpec{.kind = DamageKind::Bump, .center = c, .radius = 3, .depth = 0.8}});
    compute_vertex_normals(rough);
    f = lone(rough, RegionKind::Dent, -0.5);
    ASSERT_EQ(f.findings.size(), 1u);
    EXPECT_FALSE(f.findings[0].at_mirror_image);
    EXPECT_TRUE(f.findings[0].side_by_shape);
    EXPECT_GT(f.findings[0].roughness, kRoughnessRatio * f.findings[0].mirror_roughness);
    EXPECT_EQ(f.findings[0].side, Vec3d::UnitX());
    EXPECT_DOUBLE_EQ(f.findings[0].depth, 0.5);
}

TEST(Asymmetry, AHoleOfTheMirrorIsNoLossOfThisSide) {
    // Vertex 1 lies in a hole of the mirror that the decision read as a loss 0.4 deep: the
    // other side has no surface there, so this side against it has no value, not "less".
    AnalysisResult r;
    r.distance = {0.2f, 0.9f};
    ZoomDecision d;
    d.rule = DecisionRule::Fused;
    d.shape.value = 0.1;
    d.comparison.in_hole = {0, 1};
    d.comparison.hole_depth = {std::numeric_limits<float>::quiet_NaN(), -0.4f};
    d.comparison.hole_loss = {0, 1};
    d.comparison.lost_holes = 1;
    d.comparison.lost_hole_area = 0.5;
    d.regions.region_of_vertex = {0, 1};
    d.regions.regions = {Region{.id = 1, .peak_depth = -0.4, .kind = RegionKind::Dent}};
    d.regions.regions[0].hole = true;
    r.decisions.push_back(d);
    ASSERT_FLOAT_EQ(decided_shape(r.distance, r.decisions[0])[1], -0.4f);  // before: a loss
    as_side_against_mirror(r);
    const std::vector<float> shape = decided_shape(r.distance, r.decisions[0]);
    EXPECT_FLOAT_EQ(shape[0], -0.2f);  // outside the hole: this side minus its mirror
    EXPECT_TRUE(std::isnan(shape[1]));
    EXPECT_EQ(r.decisions[0].comparison.lost_holes, 0u);
    EXPECT_EQ(r.decisions[0].comparison.lost_hole_area, 0.0);
    EXPECT_EQ(r.decisions[0].regions.regions[0].kind, RegionKind::MissingSurface);
}

TEST(Asymmetry, SymmetricShapeHasNoFindingAndAQuietFloor) {
    const Mesh m = one_plane_shape();
    const MirrorRun r = run_asymmetry(m);
    EXPECT_TRUE(r.findings.findings.empty());
    EXPECT_LT(r.findings.floor.p95, 0.01);
}

class JawAsymmetry : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!fs::exists(kJaw)) GTEST_SKIP() << "no " << kJaw << " (shared data absent)";
    }
    // The jaw re-tessellated at its median edge, with `damage`, moved by `deg`.
    static Mesh jaw(const std::vector<DamageSpec>& damage, const Rigid& moved) {
        const Mesh original = load_mesh(kJaw).mesh;
        Mesh m = remesh_isotropic(original, {.target_edge = edge_stats(original).median});
        if (!damage.empty()) apply_damage(m, damage);
        transform_mesh(m, moved);
        return m;
    }
};

TEST_F(JawAsymmetry, CleanJawMovedAndRetessellatedHasNoRegion) {
    const Rigid moved = motion(25.0, {0.3, 1.0, -0.2}, {10, -4, 6});
    const Mesh m = jaw({}, moved);
    const MirrorRun r = run_asymmetry(m);
    expect_near_x0(r.plane.plane.plane, moved, {0, -7, 43});
    ASSERT_FALSE(r.analysis.decisions.empty());
    EXPECT_EQ(r.analysis.decisions[0].regions.regions.size(), 0u);
    EXPECT_TRUE(r.findings.findings.empty());
    std::printf("clean jaw: symmetry floor RMS %.4f, p95 %.4f\n", r.findings.floor.rms,
                r.findings.floor.p95);
}

// A loss on the right condyle: one finding, on the right (+x), "less", over the labels.
void expect_right_loss(const Mesh& m, const Rigid& moved, const char* what) {
    const MirrorRun r = run_asymmetry(m);
    expect_near_x0(r.plane.plane.plane, moved, {0, -7, 43});
    ASSERT_EQ(r.findings.findings.size(), 1u) << what;
    const AsymmetryFinding& f = r.findings.findings[0];
    EXPECT_GT((moved.linear().transpose() * f.side).x(), 0.99) << what << ": on the right (+x)";
    EXPECT_LT(f.depth, 0.0) << what;
    const double f1 = f1_of(m, r.analysis.decisions[0].regions, f.region);
    EXPECT_GE(f1, 0.9) << what;
    std::printf("%s: %s, F1 %.3f, roughness %.4g vs mirror %.4g\n", what,
                describe(f, "+x side", "-x side", "mm").c_str(), f1, f.roughness,
                f.mirror_roughness);
}

TEST_F(JawAsymmetry, DentOnTheRightCondyleIsOneFindingOnTheRight) {
    const Rigid moved = motion(15.0, {1.0, 0.4, 0.3}, {-6, 3, 12});
    expect_right_loss(
        jaw({DamageSpec{
                .kind = DamageKind::Dent, .center = kRightCondyle, .radius = 2.5, .depth = 0.4}},
            moved),
        moved, "dent");
}

TEST_F(JawAsymmetry, FlatteningOfTheRightCondyleIsOneFindingOnTheRight) {
    const Rigid moved = motion(28.0, {-0.2, 0.5, 1.0}, {4, 9, -3});
    expect_right_loss(
        jaw({DamageSpec{
                .kind = DamageKind::Flatten, .center = kRightCondyle, .radius = 3.0, .depth = 0.4}},
            moved),
        moved, "flattening");
}

// A bump on the right is the same asymmetry as a loss on the left; the bump's side bends less
// evenly, so the finding is shown there: more than the mirrored left.
TEST_F(JawAsymmetry, BumpOnTheRightIsOneFindingOnTheRight) {
    const Rigid moved = motion(12.0, {0.6, -1.0, 0.2}, {2, -8, 5});
    const Mesh m =
        jaw({DamageSpec{
                .kind = DamageKind::Bump, .center = kRightCondyle, .radius = 2.5, .depth = 0.4}},
            moved);
    const MirrorRun r = run_asymmetry(m);
    expect_near_x0(r.plane.plane.plane, moved, {0, -7, 43});
    ASSERT_EQ(r.findings.findings.size(), 1u);
    const AsymmetryFinding& f = r.findings.findings[0];
    EXPECT_GT((moved.linear().transpose() * f.side).x(), 0.99) << "on the right (+x)";
    EXPECT_GT(f.depth, 0.0) << "more than the mirrored left";
    EXPECT_TRUE(f.side_by_shape);
    const double f1 = f1_of(m, r.analysis.decisions[0].regions, f.region);
    EXPECT_GE(f1, 0.9);
    std::printf("bump: %s, F1 %.3f, roughness %.4g vs mirror %.4g\n",
                describe(f, "+x side", "-x side", "mm").c_str(), f1, f.roughness,
                f.mirror_roughness);
}

}  // namespace
}  // namespace glint
