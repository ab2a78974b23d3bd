// The pictures people read (report/pictures.h, report/detail/surface_paint.h): the signed
// shape change on a symmetric diverging map over a shaded surface, regions outlined with their
// number's anchor, unseen parts hatched, and the files a sweep writes with them.
#include "report/pictures.h"
#include "report/inspect.h"

#include "image/sampled_maps.h"
#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "render/renderer.h"
#include "report/detail/canvas.h"
#include "report/detail/legend.h"
#include "report/detail/scale_bar.h"
#include "report/detail/surface_paint.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

namespace glint {
namespace {

namespace fs = std::filesystem;

Rgb pixel(const OIIO::ImageBuf& image, int x, int y) {
    Rgb c{};
    image.getpixel(x, y, c.data(), 3);
    return c;
}

Rgb pixel(const Canvas& image, int x, int y) { return image.rgb(x, y); }

// A sphere seen from +y; distance = x (signed, so +x is a gain, −x a loss); a region on the
// +z cap; the −z cap unseen.
struct PaintedSphere {
    Mesh mesh = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 4});
    View view = make_view(
        mesh, ViewSpec{.azimuth_deg = 90, .elevation_deg = 0, .width = 160, .height = 160});
    std::vector<float> distance;
    std::vector<std::int32_t> region;
    std::vector<std::uint8_t> seen;
    detail::PaintedSurface painted;

    PaintedSphere() {
        for (const auto& p : mesh.positions) {
            distance.push_back(p.x() / 10.0f);
            region.push_back(p.z() > 7.0f ? 4 : 0);
            seen.push_back(p.z() < -7.0f ? 0 : 1);
        }
        Renderer renderer(mesh, RenderOptions{.backend = Backend::Embree, .supersample = 2});
        const Frame frame = renderer.render(view);
        painted =
            detail::paint_surface(mesh, frame, view, {distance, region, seen}, {.limit = 1.0});
    }
    // The pixel under the surface point in direction (x, y, z) from the centre (radius 10).
    [[nodiscard]] Rgb at(double x, double y, double z) const {
        const Eigen::Vector3d uv = view.camera.project(Vec3d(x, y, z).normalized() * 10.0);
        return pixel(painted.image, static_cast<int>(uv.x()), static_cast<int>(uv.y()));
    }
};

TEST(SurfacePaint, GainIsRedLossIsBlueAndNoChangeIsNearWhiteShaded) {
    const PaintedSphere s;
    const Rgb gain = s.at(0.8, 1, 0), loss = s.at(-0.8, 1, 0), none = s.at(0, 1, 0.1);
    EXPECT_GT(gain[0], gain[2] + 0.2f) << "gain should be red";
    EXPECT_GT(loss[2], loss[0] + 0.2f) << "loss should be blue";
    EXPECT_NEAR(none[0], none[2], 0.06f) << "no change should be neutral";
    EXPECT_GT(none[0], 0.5f);
    // Shading: the same colour darkens where the surface turns away from the light (upper left).
    const Rgb lit = s.at(-0.3, 1, 0.4), dim = s.at(0.3, 1, -0.5);
    EXPECT_GT(lit[0] + lit[1] + lit[2], dim[0] + dim[1] + dim[2] + 0.3f);
}

TEST(SurfacePaint, UnseenIsHatchedGreyAndTheBackgroundIsPlain) {
    const PaintedSphere s;
    // Along a row through the unseen cap the pixels alternate between two greys.
    const Eigen::Vector3d uv = s.view.camera.project(Vec3d(0, 1, -1.6).normalized() * 10.0);
    // (shading scales both greys alike: a stripe is half as bright as its neighbours)
    std::vector<float> row;
    for (int x = static_cast<int>(uv.x()) - 10; x < static_cast<int>(uv.x()) + 10; ++x) {
        const Rgb c = pixel(s.painted.image, x, static_cast<int>(uv.y()));
        EXPECT_NEAR(c[0], c[2], 0.02f) << "unseen is grey at x " << x;
        row.push_back(c[0]);
    }
    const float brightest = *std::max_element(row.begin(), row.end());
    const auto stripes =
        std::count_if(row.begin(), row.end(), [&](float g) { return g < 0.7f * brightest; });
    const auto plain = static_cast<std::ptrdiff_t>(row.size()) - stripes;
    EXPECT_GT(stripes, 2);
    EXPECT_GT(plain, 6);
    const Rgb corner = pixel(s.painted.image, 1, 1);
    // The background exactly, as 8 bits store it.
    for (int k = 0; k < 3; ++k)
        EXPECT_FLOAT_EQ(corner[k], static_cast<float>(to_byte(detail::kBackground[k])) / 255.0f);
}

TEST(SurfacePaint, RegionsAreOutlinedAndAnchoredInside) {
    const PaintedSphere s;
    ASSERT_EQ(s.painted.anchors.size(), 1u);
    const auto& a = s.painted.anchors[0];
    EXPECT_EQ(a.id, 4);
    EXPECT_GT(a.pixels, 50u);
    EXPECT_LE(a.min_x, a.x);
    EXPECT_GE(a.max_x, a.x);
    // Walking down from the anchor, the contour is crossed: dark outline pixels, then surface.
    int dark = 0;
    for (int y = a.y; y < a.max_y + 4; ++y) {
        const Rgb c = pixel(s.painted.image, a.x, y);
        if (c[0] + c[1] + c[2] < 0.15f) ++dark;
    }
    EXPECT_GE(dark, 1);
    EXPECT_LE(dark, 3);
    const Rgb inside = pixel(s.painted.image, a.x, a.y);
    EXPECT_GT(inside[0] + inside[1] + inside[2], 0.9f) << "the region's inside keeps its colour";
}

// The back of an open surface (a square facing +z, seen from below) is drawn dark, in the
// colour of the legend's swatch for it.
TEST(Legend, ShowsTheDarkBackOfAnOpenSurfaceAsPictured) {
    Mesh square;
    square.positions = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
    square.triangles = {{0, 1, 2}, {0, 2, 3}};
    square.normals.assign(4, Vec3f(0, 0, 1));
    square.unit = "mm";
    const View below = make_view(square, ViewSpec{.azimuth_deg = 0,
                                                  .elevation_deg = -90,
                                                  .width = 64,
                                                  .height = 64,
                                                  .up = Vec3d(0, 1, 0)});
    Renderer renderer(square, RenderOptions{.backend = Backend::Embree});
    const std::vector<float> distance(4, 0.0f);
    const std::vector<std::int32_t> region(4, 0);
    const std::vector<std::uint8_t> seen(4, 1);
    const auto painted =
        detail::paint_surface(square, renderer.render(below), below, {distance, region, seen}, {});
    const Rgb swatch = pixel(detail::canvas(1, 1, detail::back_face_colour()), 0, 0);
    EXPECT_EQ(pixel(painted.image, 32, 32), swatch);
    EXPECT_LT(swatch[0], 0.4f) << "dark";
    // The legend holds a block of that colour (its swatch, 14 × 14 pixels).
    detail::LegendContent legend;
    legend.unit = "mm";
    const Canvas sheet = detail::framed_sheet(10, 10, "", legend);
    int block = 0;
    for (int y = 0; y < sheet.height(); ++y)
        for (int x = 0; x < sheet.width(); ++x)
            if (pixel(sheet, x, y) == swatch) ++block;
    EXPECT_GE(block, 12 * 12);
}

TEST(DivergingImage, IsSymmetricAndClampedBeyondTheRange) {
    const std::vector<float> v{-2.0f, -1.0f, 0.0f, 1.0f, 2.0f, kNaN};
    const Canvas img = detail::diverging_image(v, 6, 1, 1.0);
    const Rgb lo = pixel(img, 0, 0), lo1 = pixel(img, 1, 0), mid = pixel(img, 2, 0),
              hi = pixel(img, 4, 0);
    for (int k = 0; k < 3; ++k) {
        EXPECT_FLOAT_EQ(lo[k], lo1[k]);
        EXPECT_NEAR(mid[k], 247.0f / 255.0f, 1e-4f);   // RdBu's centre
        EXPECT_FLOAT_EQ(pixel(img, 5, 0)[k], mid[k]);  // NaN: no change
    }
    EXPECT_NEAR(lo[2], 172.0f / 255.0f, 1e-4f);  // #2166ac
    EXPECT_NEAR(hi[0], 178.0f / 255.0f, 1e-4f);  // #b2182b
}

// The maps sampled at build time (image/sampled_maps.h: the atlas files' colours and
// report.html's scales, drawn without the image library) are OpenImageIO's: at each sample
// exactly, between samples the interpolation within a hair of the map (inferno is a smooth
// curve, so linear steps 1/1024 long stay within 1e-4 of it; the diverging map is linear there).
TEST(SampledMaps, AreOpenImageIOsColourMaps) {
    std::vector<float> t;
    for (int i = 0; i <= kSampledIntervals; ++i)
        t.push_back(static_cast<float>(i) / kSampledIntervals);
    for (int i = 0; i < 3000; ++i) t.push_back(static_cast<float>(std::fmod(i * 0.618034, 1.0)));
    const std::vector<float> inferno = color_map(t, "inferno");
    const std::vector<float> diverging = color_map(t, detail::diverging_knots());
    for (std::size_t i = 0; i < t.size(); ++i) {
        const bool on_sample = i <= static_cast<std::size_t>(kSampledIntervals);
        const Rgb a = sampled_colour(SampledMap::Inferno, t[i]);
        const Rgb b = sampled_colour(SampledMap::Diverging, t[i]);
        for (std::size_t k = 0; k < 3; ++k) {
            if (on_sample) ASSERT_EQ(a[k], inferno[3 * i + k]) << "inferno sample " << i;
            else ASSERT_NEAR(a[k], inferno[3 * i + k], 1e-4f) << "inferno at " << t[i];
            ASSERT_NEAR(b[k], diverging[3 * i + k], 2e-6f) << "diverging at " << t[i];
        }
    }
    // NaN and out-of-range values are clamped as the pictures clamp them.
    EXPECT_EQ(sampled_colour(SampledMap::Inferno, -3.0), sampled_colour(SampledMap::Inferno, 0.0));
    EXPECT_EQ(sampled_colour(SampledMap::Inferno, 7.0), sampled_colour(SampledMap::Inferno, 1.0));
    EXPECT_EQ(sampled_colour(SampledMap::Diverging, std::nan("")),
              sampled_colour(SampledMap::Diverging, 0.0));
}

// The table the pictures colour pixels with gives OpenImageIO's colours (its color_map on the
// same knots, through the image plugin): every value of a fine sweep across (and beyond) the
// range, the knots, NaN, and a range other than 1.
TEST(DivergingTable, GivesTheColourMapsOwnColours) {
    std::vector<float> v;
    for (int i = -1300; i <= 1300; ++i) v.push_back(static_cast<float>(i) * 0.0017f);
    for (int k = 0; k <= 8; ++k) v.push_back(-2.5f + 5.0f * static_cast<float>(k) / 8.0f);
    v.push_back(kNaN);
    for (const double limit : {1.0, 2.5, 0.003}) {
        std::vector<float> scaled(v);
        for (float& x : scaled) x *= static_cast<float>(limit);
        const auto w = static_cast<int>(scaled.size());
        std::vector<float> t(scaled.size());
        for (std::size_t i = 0; i < t.size(); ++i)
            t[i] = std::isnan(scaled[i])
                       ? 0.5f
                       : static_cast<float>(std::clamp(0.5 + 0.5 * scaled[i] / limit, 0.0, 1.0));
        const std::vector<float> rgb = color_map(t, detail::diverging_knots());
        const auto& table = detail::DivergingTable::get();
        for (int i = 0; i < w; ++i) {
            const auto at = 3 * static_cast<std::size_t>(i);
            const Rgb want{rgb[at], rgb[at + 1], rgb[at + 2]};
            const Rgb got = table(scaled[static_cast<std::size_t>(i)], limit);
            for (int k = 0; k < 3; ++k)
                ASSERT_NEAR(got[k], want[k], 2e-6f)
                    << "value " << scaled[static_cast<std::size_t>(i)] << " range " << limit;
        }
    }
}

TEST(Canvas, IsEightBitAndEncodesAsItIs) {
    const Canvas c = detail::canvas(7, 5, {1.0f, 0.5f, 0.0f});
    EXPECT_EQ(c.channels(), 3);
    EXPECT_EQ(c.pixels().size(), 7u * 5u * 3u);
    const std::string png = encode_png(c);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
    // OpenImageIO reads the bytes back as the canvas holds them.
    OIIO::Filesystem::IOMemReader reader(png.data(), png.size());
    OIIO::ImageBuf back("picture.png", 0, 0, nullptr, nullptr, &reader);
    ASSERT_TRUE(back.read(0, 0, true, OIIO::TypeDesc::UINT8)) << back.geterror();
    ASSERT_EQ(back.spec().width, 7);
    ASSERT_EQ(back.spec().height, 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) EXPECT_EQ(pixel(back, x, y), pixel(c, x, y));
    const Rgb p = pixel(c, 6, 4);
    EXPECT_FLOAT_EQ(p[0], 1.0f);
    EXPECT_FLOAT_EQ(p[1], 128.0f / 255.0f);  // 0.5 rounded as OpenImageIO converts
    EXPECT_FLOAT_EQ(p[2], 0.0f);
    EXPECT_EQ(to_byte(0.5f), 128);
    EXPECT_EQ(to_byte(-1.0f), 0);
    EXPECT_EQ(to_byte(2.0f), 255);
}

// A legend listing more regions than its panel holds, on the smallest sheet, with long lines
// (the bunny's 14 "missing surface" regions aborted in OpenImageIO's render_text once: text
// below the image). Text that does not fit is left out; nothing aborts.
TEST(Legend, ManyRegionsOnASmallSheetAreCutNotDrawnOffTheImage) {
    detail::LegendContent legend;
    legend.unit = "mm";
    legend.lines.assign(6, "normal floor 8.12 deg (measured; median + 3 MAD over compared)");
    for (int i = 1; i <= 40; ++i)
        legend.regions.push_back(std::to_string(i) + " missing surface, 0.0123 mm2");
    const Canvas sheet = detail::framed_sheet(64, 32, "", legend);
    EXPECT_GE(sheet.height(), detail::legend_min_height(legend));
    Canvas c = detail::canvas(40, 20);
    detail::draw_text(c, 5, 60, "below the image", 12);
    detail::draw_text(c, 2, 24, "half below", 12);
    detail::draw_text(c, 35, 15, "past the right edge", 12);
    detail::draw_text(c, 20, -5, "above", 12, detail::kText, detail::TextAlign::Center);
    EXPECT_EQ(pixel(c, 39, 19), pixel(detail::canvas(40, 20), 39, 19));
}

AnalysisResult result_with(std::vector<double> peaks, double floor) {
    AnalysisResult r;
    r.size = 100.0;
    r.sweep.zooms.resize(1);
    r.decisions.resize(1);
    r.decisions[0].rule = DecisionRule::Fused;
    r.decisions[0].shape.value = floor;
    int id = 0;
    for (double p : peaks)
        r.decisions[0].regions.regions.push_back(Region{.id = ++id, .peak_depth = p});
    return r;
}

TEST(ShapeScale, FollowsTheMedianRegionPeakRoundedUpAndNeverBelowTwiceTheFloor) {
    EXPECT_DOUBLE_EQ(shape_scale(result_with({-0.41}, 0.02)).limit, 0.5);
    EXPECT_DOUBLE_EQ(shape_scale(result_with({-30.0, 2.9, 0.3}, 0.02)).limit, 3.0);
    EXPECT_DOUBLE_EQ(shape_scale(result_with({0.05}, 0.04)).limit, 0.08);
    EXPECT_EQ(shape_scale(result_with({0.05}, 0.04)).source, "twice the shape floor");
    // No region: the 99th percentile of |distance| over seen vertices.
    AnalysisResult r = result_with({}, 0.0);
    for (int i = 0; i < 1000; ++i)
        r.distance.push_back(i % 2 ? 0.001f * static_cast<float>(i) : -0.5f);
    r.sweep.zooms[0].coverage.seen.assign(1000, 1);
    r.distance[7] = 100.0f;  // one outlier does not set the range
    EXPECT_DOUBLE_EQ(shape_scale(r).limit, 1.0);
    EXPECT_EQ(shape_scale(r).source, "99th percentile of |distance|");
}

TEST(Pictures, ASweepWritesAtlasMosaicAndViewsWithTheDentInBlue) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "pictures";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const Mesh ref = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 4});
    Mesh exa = ref;
    apply_damage(
        exa,
        {DamageSpec{.kind = DamageKind::Dent, .center = {10, 0, 0}, .radius = 3.0, .depth = 0.5}});
    InspectOptions inspect_options;
    AnalysisOptions& options = inspect_options.analysis;
    options.fit.mode = FitMode::Identity;
    options.sweep.plan.azimuth_step_deg = 90;
    options.sweep.plan.elevations_deg = {0};
    options.sweep.plan.size = 64;
    options.sweep.render.backend = Backend::Embree;
    inspect_options.exports.output = dir / "atlas";
    inspect_options.exports.write_views = true;
    const AnalysisResult result = inspect(ref, exa, inspect_options, {}).analysis;
    ASSERT_EQ(result.decisions[0].regions.regions.size(), 1u);
    const int best = result.decisions[0].regions.regions[0].best_view;
    ASSERT_GE(best, 0);
    EXPECT_TRUE(fs::exists(dir / "atlas" / "report.html"));
    const std::string best_picture =
        "views/" + view_file_stem(result.sweep.plan.views[static_cast<std::size_t>(best)].view) +
        ".png";
    for (const std::string& f :
         {std::string("atlas.png"), std::string("mosaic_z0.png"), best_picture}) {
        OIIO::ImageBuf img((dir / "atlas" / f).string());
        ASSERT_TRUE(img.read()) << f << ": " << img.geterror();
        // The dent shows blue: pixels clearly bluer than red (the legend's bar has some too,
        // so the picture must hold more than the bar's lower half).
        // Every panel, close-up and view carries a scale bar in its own colour.
        const Rgb bar_colour = pixel(detail::canvas(1, 1, detail::kScaleBarColour), 0, 0);
        int blue = 0, scale_bar = 0;
        for (int y = 0; y < img.spec().height; ++y)
            for (int x = 0; x < img.spec().width - detail::kLegendWidth; ++x) {
                const Rgb c = pixel(img, x, y);
                if (c[2] > c[0] + 0.15f) ++blue;
                if (c == bar_colour) ++scale_bar;
            }
        EXPECT_GT(blue, 20) << f;
        if (f != "mosaic_z0.png") {
            EXPECT_GT(scale_bar, 4 * 10) << f;
        }
    }
}

}  // namespace
}  // namespace glint
