// The scale bar of the pictures (report/detail/scale_bar.h): a round length whose pixels
// measure what the picture's projection maps that length to, checked against a sphere of
// known radius drawn in the same picture.
#include "report/detail/scale_bar.h"

#include "mesh/phantom.h"
#include "render/renderer.h"
#include "report/detail/surface_paint.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

Rgb pixel(const Canvas& image, int x, int y) { return image.rgb(x, y); }

bool is_bar(const Rgb& c) {
    return std::abs(c[0] - detail::kScaleBarColour[0]) < 0.02f &&
           std::abs(c[1] - detail::kScaleBarColour[1]) < 0.02f && c[2] < 0.02f;
}

// The longest run of bar pixels in any row, and how many rows hold one that long.
struct BarRun {
    int pixels = 0;
    int rows = 0;
};
BarRun longest_bar_run(const Canvas& image) {
    BarRun best;
    for (int y = 0; y < image.height(); ++y) {
        int run = 0, longest = 0;
        for (int x = 0; x < image.width(); ++x) {
            run = is_bar(pixel(image, x, y)) ? run + 1 : 0;
            longest = std::max(longest, run);
        }
        if (longest > best.pixels) best = {longest, 0};
        if (longest == best.pixels && longest > 0) ++best.rows;
    }
    return best;
}

bool is_round(double length) {
    const double m = length / std::pow(10.0, std::floor(std::log10(length) + 1e-9));
    return std::abs(m - 1) < 1e-9 || std::abs(m - 2) < 1e-9 || std::abs(m - 5) < 1e-9;
}

TEST(ScaleBar, RoundLengthsAreOneTwoOrFiveTimesAPowerOfTen) {
    EXPECT_DOUBLE_EQ(detail::round_length_at_most(7.3), 5.0);
    EXPECT_DOUBLE_EQ(detail::round_length_at_most(0.19), 0.1);
    EXPECT_DOUBLE_EQ(detail::round_length_at_most(2.0), 2.0);
    EXPECT_DOUBLE_EQ(detail::round_length_at_most(99.0), 50.0);
    EXPECT_NEAR(detail::round_length_at_most(0.003), 0.002, 1e-15);
    EXPECT_EQ(detail::scale_bar_label(10.0, "mm", false), "10 mm");
    EXPECT_EQ(detail::scale_bar_label(0.5, "mm", true), "0.5 mm at front");
    const auto bar = detail::scale_bar(0.25, 50, "mm");  // 12.5 mm fit: a 10 mm bar, 40 px
    EXPECT_DOUBLE_EQ(bar.length, 10.0);
    EXPECT_EQ(bar.pixels, 40);
    EXPECT_EQ(bar.label, "10 mm");
    EXPECT_EQ(detail::scale_bar(0.0, 50, "mm").pixels, 0);
    EXPECT_EQ(detail::scale_bar(std::nan(""), 50, "mm").pixels, 0);
}

// A sphere of radius 10 seen orthographically: the bar's pixels over the silhouette's
// diameter in pixels are the bar's length over 20.
TEST(ScaleBar, MeasuresWhatTheProjectionMapsItsLengthTo) {
    const Mesh mesh = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 5});
    const View view = make_view(
        mesh, ViewSpec{.azimuth_deg = 90, .elevation_deg = 0, .width = 200, .height = 200});
    const std::vector<float> distance(mesh.vertex_count(), 0.0f);
    const std::vector<std::int32_t> region(mesh.vertex_count(), 0);
    const std::vector<std::uint8_t> seen(mesh.vertex_count(), 1);
    Renderer renderer(mesh, RenderOptions{.backend = Backend::Embree});
    const Frame frame = renderer.render(view);
    auto painted = detail::paint_surface(mesh, frame, view, {distance, region, seen}, {});
    detail::draw_view_scale_bar(painted.image, 0, 0, view, "mm");

    const detail::ScaleBar bar = detail::view_scale_bar(view, "mm");
    ASSERT_GT(bar.pixels, 0);
    EXPECT_TRUE(is_round(bar.length)) << bar.length;
    EXPECT_EQ(bar.label, detail::format_number(bar.length) + " mm");
    // The longest round length a quarter of the width holds: above 0.4 of that quarter.
    EXPECT_LE(bar.pixels, view.camera.width / 4);
    EXPECT_GT(bar.pixels, view.camera.width / 10);

    const BarRun found = longest_bar_run(painted.image);
    EXPECT_EQ(found.pixels, bar.pixels);
    EXPECT_EQ(found.rows, detail::kScaleBarThickness);
    // The silhouette's width through the sphere's centre, in pixels.
    const Eigen::Vector3d centre = view.camera.project(Vec3d::Zero());
    int diameter_px = 0;
    for (int x = 0; x < frame.width; ++x)
        if (frame.coverage[static_cast<std::size_t>(static_cast<int>(centre.y()) * frame.width +
                                                    x)] > 0.5f)
            ++diameter_px;
    const double measured_length = 20.0 * found.pixels / diameter_px;
    EXPECT_NEAR(measured_length, bar.length, 0.03 * bar.length)
        << found.pixels << " px of bar, " << diameter_px << " px across the sphere";
}

TEST(ScaleBar, PerspectivePicturesSayWhereTheBarIsTrue) {
    const Mesh mesh = make_phantom({.kind = PhantomKind::Sphere});
    const View view = make_view(
        mesh, ViewSpec{.width = 200, .height = 200, .projection = Projection::Perspective});
    EXPECT_DOUBLE_EQ(detail::picture_units_per_px(view), view.footprint);
    const detail::ScaleBar bar = detail::view_scale_bar(view, "mm");
    EXPECT_NE(bar.label.find("at front"), std::string::npos) << bar.label;
    EXPECT_NEAR(bar.pixels * view.footprint, bar.length, view.footprint);
}

}  // namespace
}  // namespace glint
