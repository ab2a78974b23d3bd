// The symmetry plane on a picture (report/detail/symmetry_plane_trace.h, glint asymmetry's
// atlas.png): drawn where the plane projects, on the surface and, seen edge-on, across the
// background; off the regions; labelled only where it is a line across the picture.
#include "report/detail/symmetry_plane_trace.h"

#include "mesh/phantom.h"
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace glint {
namespace {

constexpr int kSize = 256;
// mm per pixel: the sphere (radius 10) is 80 px across, the background around it holds the
// label
constexpr double kFootprint = 0.25;

struct Drawn {
    Canvas image;
    Frame frame;
    View view;
    std::optional<detail::PlaneLabel> label;
};

// The sphere seen from (azimuth, elevation), the plane drawn on a blank picture.
Drawn draw(const Mesh& mesh, double azimuth, double elevation,
           const std::vector<std::int32_t>& region, const MirrorPictures& plane) {
    Drawn d{.image = detail::canvas(kSize, kSize),
            .frame = {},
            .view = make_view(framing_sphere(mesh), ViewSpec{.azimuth_deg = azimuth,
                                                             .elevation_deg = elevation,
                                                             .zoom = ZoomKind::Footprint,
                                                             .zoom_value = kFootprint,
                                                             .width = kSize,
                                                             .height = kSize}),
            .label = std::nullopt};
    Renderer renderer(mesh, RenderOptions{.backend = Backend::Embree});
    renderer.render_views(std::span(&d.view, 1), [&](std::size_t, const Frame& f) { d.frame = f; });
    d.label = detail::draw_symmetry_plane(d.image, d.frame, d.view, mesh, region, plane);
    return d;
}

bool has_plane_colour(const Canvas& image, int x, int y) {
    const Rgb p = image.rgb(x, y);
    for (int k = 0; k < 3; ++k)
        if (std::abs(p[k] - detail::kSymmetryPlane[static_cast<std::size_t>(k)]) > 0.01f)
            return false;
    return true;
}

// Pixels of row y carrying the plane's colour within `reach` of column u, and beyond it.
struct RowCount {
    int near = 0;
    int far = 0;
};
RowCount count_row(const Canvas& image, int y, double u, double reach) {
    RowCount c;
    for (int x = 0; x < kSize; ++x)
        (std::abs(x + 0.5 - u) <= reach ? c.near : c.far) += has_plane_colour(image, x, y) ? 1 : 0;
    return c;
}

const Mesh& sphere() {
    static const Mesh m = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 4});
    return m;
}

// Seen from +y the plane x = 0 is edge-on: a vertical line through the centre, on the sphere
// and across the background, and nowhere else.
TEST(SymmetryPlaneTrace, DrawnWhereThePlaneProjects) {
    const MirrorPictures plane{.normal = {1, 0, 0}, .offset = 0.0, .residual = 0.001};
    const std::vector<std::int32_t> no_region(sphere().vertex_count(), 0);
    const Drawn d = draw(sphere(), 90, 0, no_region, plane);
    int surface_rows = 0;
    for (int y = 5; y < kSize - 5; ++y) {
        // the plane's line at this row: where a point of the plane projects
        const Ray ray = d.view.camera.pixel_ray(kSize / 2.0, y + 0.5);
        const Vec3d on_plane = ray.origin - plane.distance(ray.origin) * plane.normal;
        const double u = d.view.camera.project(on_plane).x();
        const RowCount c = count_row(d.image, y, u, 1.5);
        EXPECT_GE(c.near, 1) << "row " << y << ": no line at u = " << u;
        EXPECT_EQ(c.far, 0) << "row " << y << ": plane colour away from the line";
        surface_rows +=
            d.frame.primitive_id[static_cast<std::size_t>(y * kSize + kSize / 2)] != kNoPrimitive;
    }
    EXPECT_GT(surface_rows, kSize / 4) << "the line crosses the sphere";
    ASSERT_TRUE(d.label.has_value()) << "an edge-on plane is labelled";
    EXPECT_EQ(d.frame.primitive_id[static_cast<std::size_t>(d.label->y * kSize + d.label->x)],
              kNoPrimitive)
        << "the label lies off the surface";
}

// A region on the line keeps its colours: no plane colour on its pixels.
TEST(SymmetryPlaneTrace, LeavesTheRegionsAlone) {
    const MirrorPictures plane{.normal = {1, 0, 0}, .offset = 0.0, .residual = 0.001};
    std::vector<std::int32_t> region(sphere().vertex_count(), 0);
    for (std::size_t v = 0; v < region.size(); ++v)
        region[v] = sphere().positions[v].z() > 5.0f ? 1 : 0;  // a cap the line crosses
    const Drawn d = draw(sphere(), 90, 0, region, plane);
    int on_region = 0, elsewhere = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const auto t = d.frame.primitive_id[static_cast<std::size_t>(y * kSize + x)];
            if (!has_plane_colour(d.image, x, y)) continue;
            bool in_region = false;
            if (t != kNoPrimitive)
                for (const auto v : sphere().triangles[t]) in_region |= region[v] != 0;
            (in_region ? on_region : elsewhere) += 1;
        }
    EXPECT_EQ(on_region, 0);
    EXPECT_GT(elsewhere, kSize) << "the line is still drawn off the region";
}

// Seen obliquely the plane is no line across the picture: only its trace on the surface, no
// label; a plane that misses the surface draws nothing.
TEST(SymmetryPlaneTrace, ObliqueViewDrawsOnlyTheTraceOnTheSurface) {
    const std::vector<std::int32_t> no_region(sphere().vertex_count(), 0);
    const Drawn d = draw(sphere(), 45, 20, no_region, {.normal = {1, 0, 0}, .offset = 0.0});
    int on_surface = 0, background = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (has_plane_colour(d.image, x, y))
                (d.frame.primitive_id[static_cast<std::size_t>(y * kSize + x)] != kNoPrimitive
                     ? on_surface
                     : background) += 1;
    EXPECT_GT(on_surface, kSize / 2);
    EXPECT_EQ(background, 0);
    EXPECT_FALSE(d.label.has_value());
    const Drawn missed = draw(sphere(), 90, 0, no_region, {.normal = {1, 0, 0}, .offset = 50.0});
    for (int y = 0; y < kSize; ++y)
        EXPECT_EQ(count_row(missed.image, y, 0.0, kSize).near, 0) << "row " << y;
}

}  // namespace
}  // namespace glint
