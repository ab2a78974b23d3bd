// Landmarks given as picked pixels resolve to the surface points they show, so a fit from
// pixels reproduces the fit from the 3D points.
#include "analysis/landmarks.h"

#include "mesh/damage.h"
#include "mesh/error.h"
#include "mesh/phantom.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

// The asymmetric blob of the registration tests (ellipsoid 12×8×6 mm with two bumps).
Mesh blob() {
    Mesh m = make_phantom({.kind = PhantomKind::Ellipsoid,
                           .scheme = TessellationScheme::Ico,
                           .resolution = 4,
                           .radii = {12, 8, 6}});
    apply_damage(
        m,
        {DamageSpec{.kind = DamageKind::Bump, .center = {6.9, 4.0, 3.3}, .radius = 4, .depth = 1.5},
         DamageSpec{
             .kind = DamageKind::Bump, .center = {-9.0, 0.0, -3.9}, .radius = 3, .depth = 1.0}});
    return m;
}

// A view looking at `p` along its outward direction, and the pixel that shows p there. The
// pixel comes from Camera::project (mesh/), not from the picking under test.
LandmarkSide as_pixel(const Mesh& mesh, const Vec3d& p, const Vec3d& outward, int size,
                      double footprint) {
    const Vec3d d = outward.normalized();
    LandmarkSide s;
    s.view = {.azimuth_deg = std::atan2(d.y(), d.x()) * 180 / std::numbers::pi,
              .elevation_deg = std::asin(d.z()) * 180 / std::numbers::pi,
              .size = size,
              .footprint = footprint};
    const Eigen::Vector3d uvz = pick_view(mesh, s.view).camera.project(p);
    s.u = uvz.x();
    s.v = uvz.y();
    // A user picks inside the image.
    EXPECT_TRUE(s.u > 0 && s.u < size && s.v > 0 && s.v < size)
        << "pixel (" << s.u << ", " << s.v << ")";
    return s;
}

TEST(ResolveLandmarks, PickedPixelsReproduceThePointLandmarkFit) {
    const Mesh ref = blob();
    Rigid truth = Rigid::Identity();  // reference_from_examined, far beyond ICP's reach
    truth.linear() =
        Eigen::AngleAxisd(150 * std::numbers::pi / 180, Vec3d(0.2, 1, 0.3).normalized())
            .toRotationMatrix();
    truth.translation() = Vec3d(5, 3, -2);
    Mesh exa = ref;
    transform_mesh(exa, truth.inverse());
    // Four vertices of the reference on different sides, and where they are on the examined.
    std::vector<LandmarkPair> pairs;
    std::vector<Vec3d> on_ref, on_exa;
    const Vec3d exa_centre = framing_sphere(exa).center;
    int k = 0;
    for (const std::size_t v :
         {std::size_t{0}, ref.vertex_count() / 3, ref.vertex_count() / 2, ref.vertex_count() - 7}) {
        const Vec3d p = ref.positions[v].cast<double>(), n = ref.normals[v].cast<double>();
        on_ref.push_back(p);
        on_exa.push_back(truth.inverse() * p);
        // Reference side: seen along its normal, the whole mesh framed. Examined side: every
        // other pair zoomed in (0.05 mm per pixel) and seen from the framing centre's
        // direction, so that the point lies inside the narrow image.
        const LandmarkSide exa_side =
            k++ % 2 ? as_pixel(exa, on_exa.back(), on_exa.back() - exa_centre, 200, 0.05)
                    : as_pixel(exa, on_exa.back(), truth.inverse().linear() * n, 200, 0.0);
        pairs.push_back({exa_side, as_pixel(ref, p, n, 256, 0.0)});
    }
    const ClosestPointIndex ref_index(ref), exa_index(exa);
    const ResolvedLandmarks r = resolve_landmarks(pairs, ref_index, exa_index, "test");
    ASSERT_EQ(r.reference.size(), pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        // note: Embree intersects in float: 1e-4 mm on a 24 mm blob.
        EXPECT_LT((r.reference[i] - on_ref[i]).norm(), 1e-4) << "pair " << i + 1;
        EXPECT_LT((r.examined[i] - on_exa[i]).norm(), 1e-4) << "pair " << i + 1;
    }
    const Rigid from_pixels = fit_landmarks(r.examined, r.reference);
    const Rigid from_points = fit_landmarks(on_exa, on_ref);
    const Rigid d = from_points.inverse() * from_pixels;
    EXPECT_LT(rotation_angle_deg(d), 1e-3);
    EXPECT_LT(d.translation().norm(), 1e-4);
    EXPECT_LT(rotation_angle_deg(truth.inverse() * from_pixels), 1e-3);
}

TEST(ResolveLandmarks, APixelThatShowsNothingIsAnInputErrorNamingThePair) {
    const Mesh ref = blob();
    const ClosestPointIndex index(ref);
    std::vector<LandmarkPair> pairs(2);
    pairs[0].examined.point = pairs[0].reference.point = Vec3d(0, 0, 0);
    pairs[1].examined.point = Vec3d(0, 0, 0);
    pairs[1].reference.view = {.azimuth_deg = 0, .elevation_deg = 0, .size = 64};
    pairs[1].reference.u = pairs[1].reference.v = 0.5;  // the corner of a framed view: background
    try {
        (void)resolve_landmarks(pairs, index, index, "landmarks \"lm.json\"");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("lm.json"), std::string::npos) << what;
        EXPECT_NE(what.find("pair 2"), std::string::npos) << what;
        EXPECT_NE(what.find("reference"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace glint
