#include "mesh/damage.h"

#include "mesh/error.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

Mesh sphere(int level = 5) {
    return make_phantom({.kind = PhantomKind::Sphere,
                         .scheme = TessellationScheme::Ico,
                         .resolution = level,
                         .radii = {10, 10, 10}});
}

const std::vector<float>& gt(const Mesh& m) { return m.find_scalar("gt_displacement")->values; }

// Expects InputError holding every fragment.
template <class F>
void expect_input_error(F&& f, std::initializer_list<const char*> fragments) {
    try {
        f();
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        for (const char* frag : fragments)
            EXPECT_NE(std::string(e.what()).find(frag), std::string::npos) << e.what();
    }
}

TEST(ApplyDamage, DentIsInwardLabelledAndLocal) {
    Mesh m = sphere();
    const Mesh before = m;
    apply_damage(
        m, {DamageSpec{.kind = DamageKind::Dent, .center = {10, 0, 0}, .radius = 3, .depth = 0.5}});
    double min_disp = 0.0;
    std::size_t labelled = 0;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        const double d = gt(m)[v];
        const double r = (before.positions[v] - Vec3f(10, 0, 0)).norm();
        min_disp = std::min(min_disp, d);
        if (r >= 3.0 + 1e-4) {
            EXPECT_EQ(d, 0.0f) << "vertex " << v << " moved outside the radius";
            EXPECT_EQ(m.positions[v], before.positions[v]);
        }
        // Labels exactly where |displacement| > kDamageLabelThreshold of the depth.
        EXPECT_EQ(m.labels[v] != 0, std::abs(d) > kDamageLabelThreshold * 0.5) << v;
        labelled += m.labels[v] != 0;
        // Moved along the normal: the radius shrinks by the displacement.
        EXPECT_NEAR(m.positions[v].norm(), 10.0 + d, 1e-4);
    }
    // The centre lies on a face; the nearest vertex (within ~0.2 mm) moves by ≥ 99% of the depth.
    EXPECT_NEAR(min_disp, -0.5, 0.005);
    EXPECT_GT(labelled, 20u);
    EXPECT_EQ(m.find_scalar("gt_label")->values.size(), m.vertex_count());
}

TEST(ApplyDamage, BumpIsOutward) {
    Mesh m = sphere();
    apply_damage(
        m, {DamageSpec{.kind = DamageKind::Bump, .center = {0, 0, 10}, .radius = 2, .depth = 0.3}});
    EXPECT_NEAR(*std::max_element(gt(m).begin(), gt(m).end()), 0.3, 1e-6);
    EXPECT_GE(*std::min_element(gt(m).begin(), gt(m).end()), 0.0f);
}

TEST(ApplyDamage, PitHasAFlatBottom) {
    Mesh m = sphere(6);
    apply_damage(
        m, {DamageSpec{.kind = DamageKind::Pit, .center = {10, 0, 0}, .radius = 2, .depth = 0.4}});
    std::size_t at_full_depth = 0;
    for (float d : gt(m)) at_full_depth += std::abs(d + 0.4f) < 1e-5f;
    EXPECT_GT(at_full_depth, 10u);  // many vertices at the full depth: a flat floor
}

TEST(ApplyDamage, GrooveFollowsItsPath) {
    Mesh m = sphere(6);
    apply_damage(m, {DamageSpec{.kind = DamageKind::Groove,
                                .radius = 0.8,
                                .depth = 0.2,
                                .path = {{10, -3, 0}, {9.5, 0, 3}}}});
    // Something along the path moved, nothing far from it did.
    std::size_t moved = 0;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        if (gt(m)[v] != 0.0f) {
            ++moved;
            EXPECT_LT(m.positions[v].x(), 10.0f);
            EXPECT_GT(m.positions[v].x(), 8.0f);
        }
    }
    EXPECT_GT(moved, 20u);
}

TEST(ApplyDamage, FlattenCutsAPlaneAtTheDepth) {
    Mesh m = sphere(6);
    apply_damage(m, {DamageSpec{.kind = DamageKind::Flatten,
                                .center = {0, 0, 10},
                                .radius = 4,
                                .depth = 0.5,
                                .plane_normal = Vec3d{0, 0, 1}}});
    float top = -1e9f;
    for (const auto& p : m.positions) top = std::max(top, p.z());
    EXPECT_NEAR(top, 9.5f, 1e-4f);
}

TEST(ApplyDamage, FlattenWithoutANormalCutsAcrossTheSurfaceAsItFaces) {
    // The tip of a sphere at +x: the plane faces +x, 0.5 below the tip, and no vertex moves
    // by more than the depth (a plane of another direction would fold the surface over).
    Mesh m = sphere(6);
    const Mesh before = m;
    apply_damage(
        m,
        {DamageSpec{.kind = DamageKind::Flatten, .center = {10, 0, 0}, .radius = 4, .depth = 0.5}});
    float tip = -1e9f, moved = 0.0f;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        tip = std::max(tip, m.positions[v].x());
        moved = std::max(moved, (m.positions[v] - before.positions[v]).norm());
    }
    EXPECT_NEAR(tip, 9.5f, 1e-4f);
    EXPECT_LE(moved, 0.5f + 1e-4f);
}

TEST(ApplyDamage, ErosionIsRoughDeterministicAndALoss) {
    Mesh a = sphere(6), b = sphere(6), c = sphere(6);
    const DamageSpec e{
        .kind = DamageKind::Erosion, .center = {10, 0, 0}, .radius = 3, .depth = 0.4, .seed = 7};
    apply_damage(a, {e});
    apply_damage(b, {e});
    DamageSpec other = e;
    other.seed = 8;
    apply_damage(c, {other});
    EXPECT_EQ(gt(a), gt(b));
    EXPECT_NE(gt(a), gt(c));
    EXPECT_LE(*std::max_element(gt(a).begin(), gt(a).end()), 0.0f);
}

TEST(ApplyDamage, NoiseIsNotLabelled) {
    Mesh m = sphere();
    apply_damage(m, {DamageSpec{.kind = DamageKind::Noise, .sigma = 0.01, .seed = 3}});
    for (auto l : m.labels) EXPECT_EQ(l, 0);
}

TEST(ApplyDamage, RejectsADamageOutsideTheSurface) {
    Mesh m = sphere();
    expect_input_error(
        [&] {
            apply_damage(m, {DamageSpec{.center = {30, 0, 0}, .radius = 2, .depth = 0.1}});
        },
        {"damage 1", "outside the surface"});
}

TEST(ApplyDamage, RejectsNonPositiveSizesNamingTheField) {
    Mesh m = sphere(2);
    expect_input_error(
        [&] {
            apply_damage(m, {DamageSpec{.center = {10, 0, 0}, .radius = 2, .depth = -0.1}});
        },
        {"depth"});
    expect_input_error(
        [&] {
            apply_damage(m, {DamageSpec{.center = {10, 0, 0}, .radius = 0, .depth = 0.1}});
        },
        {"radius"});
    expect_input_error(
        [&] {
            apply_damage(
                m,
                {DamageSpec{
                    .kind = DamageKind::Groove, .radius = 1, .depth = 0.1, .path = {{10, 0, 0}}}});
        },
        {"path"});
}

TEST(ParseDamageSpec, ReadsEveryKeyAndRejectsTypos) {
    const DamageSpec d = parse_damage_spec("erosion:center=1,2,3;radius=4;depth=0.5;seed=9");
    EXPECT_EQ(d.kind, DamageKind::Erosion);
    EXPECT_EQ(d.center, Vec3d(1, 2, 3));
    EXPECT_EQ(d.radius, 4.0);
    EXPECT_EQ(d.seed, 9u);
    EXPECT_EQ(parse_damage_spec("groove:path=0,0,0/1,1,1/2,2,2;radius=1").path.size(), 3u);
    EXPECT_EQ(parse_damage_spec("dent:center=1,2,3 radius=4 depth=0.5").radius,
              4.0);  // spaces separate too
    expect_input_error([] { (void)parse_damage_spec("dent:center=1,2,3;raduis=4"); },
                       {"raduis", "unknown key"});
    expect_input_error([] { (void)parse_damage_spec("dint:center=1,2,3"); },
                       {"dint", "unknown kind"});
    expect_input_error([] { (void)parse_damage_spec("dent:center=1,2"); }, {"center", "x,y,z"});
    expect_input_error([] { (void)parse_damage_spec("dent:depth=abc"); },
                       {"depth", "not a number"});
}

TEST(ParsePoseSpec, BuildsProperRigidMotions) {
    const Rigid a = parse_pose_spec("0,0,90,1,2,3");
    EXPECT_TRUE((a * Vec3d(1, 0, 0)).isApprox(Vec3d(1, 3, 3), 1e-12));
    EXPECT_NEAR(a.linear().determinant(), 1.0, 1e-12);
    const Rigid b = parse_pose_spec("axis=0,0,1;angle=90;t=1,2,3");
    EXPECT_TRUE(a.isApprox(b, 1e-12));
    EXPECT_THROW((void)parse_pose_spec("1,2,3"), InputError);
    EXPECT_THROW((void)parse_pose_spec("axis=0,0,0;angle=5"), InputError);
}

}  // namespace
}  // namespace glint
