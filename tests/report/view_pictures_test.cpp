// What each view measured (report/view_measurements.h) and the pictures drawn from it
// (issue 26): per-view PNGs show the view's own signed depth, not the atlas redrawn; the
// mosaic is a chart of how much each view measured beyond its floor plus the views that saw
// the regions.
#include "report/view_measurements.h"

#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "report/detail/canvas.h"
#include "report/detail/legend.h"
#include "report/detail/measured_pixels.h"
#include "report/detail/view_chart.h"
#include "report/inspect.h"
#include "report/output_folder.h"
#include "report/pictures.h"

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

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

// The map's loss side: clearly bluer than red and than green (the legend's violet, the
// examined-only green and the greys are not).
bool is_blue(const Rgb& c) { return c[2] > c[0] + 0.15f && c[2] > c[1]; }

SweepPlan plan_of(std::vector<int> sizes, int views_per_zoom) {
    SweepPlan plan;
    plan.sizes = sizes;
    for (std::size_t z = 0; z < sizes.size(); ++z)
        for (int k = 0; k < views_per_zoom; ++k) {
            PlannedView pv;
            pv.view.index = static_cast<int>(plan.views.size());
            pv.view.zoom_index = static_cast<int>(z);
            pv.view.camera.width = pv.view.camera.height = sizes[z];
            plan.views.push_back(pv);
        }
    return plan;
}

// A w × h map: the left half compared at depth −1 (metric 10), the right half reference only.
DeviationMap half_and_half(int w, int h) {
    DeviationMap d;
    d.width = w;
    d.height = h;
    const auto n = static_cast<std::size_t>(w * h);
    d.angle_deg.assign(n, kNaN);
    d.signed_depth.assign(n, kNaN);
    d.silhouette.assign(n, 0);
    for (std::size_t p = 0; p < n; ++p) {
        if (static_cast<int>(p % static_cast<std::size_t>(w)) < w / 2) {
            d.angle_deg[p] = 10.0f;
            d.signed_depth[p] = -1.0f;
        } else {
            d.silhouette[p] = static_cast<std::uint8_t>(Silhouette::ReferenceOnly);
        }
    }
    summarise(d);
    return d;
}

TEST(ViewMeasurements, KeepsEachViewReducedToItsPictureSizeWithinTheBudget) {
    const SweepPlan plan = plan_of({1024}, 2);
    ViewMeasurements store(plan);
    store.add(plan.views[0], half_and_half(1024, 1024));
    const ViewMeasurement* m = store.find(0);
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->block, 2) << "1024-px frames kept at 512 cells";
    EXPECT_EQ(m->width, 512);
    EXPECT_EQ(m->status_at(10), MeasuredStatus::Compared);
    EXPECT_FLOAT_EQ(m->depth_at(10), -1.0f);
    EXPECT_FLOAT_EQ(m->value_at(10), 10.0f);
    EXPECT_EQ(m->status_at(400), MeasuredStatus::ReferenceOnly);
    EXPECT_TRUE(std::isnan(m->depth_at(400)));
    EXPECT_EQ(store.find(1), nullptr) << "a view not added has no measurement";
    EXPECT_EQ(store.bytes(), 5u * 512 * 512);
    // 300 views of 512 px in 4 MiB: coarser grids, all of them within the budget.
    const SweepPlan many = plan_of({512}, 300);
    ViewMeasurements small(many, 4u << 20);
    small.add(many.views[299], half_and_half(512, 512));
    const ViewMeasurement* coarse = small.find(299);
    ASSERT_NE(coarse, nullptr);
    EXPECT_LE(300 * small.bytes(), std::size_t{4} << 20);
    EXPECT_GE(coarse->width, 45) << "no coarser than the budget needs";
    EXPECT_FLOAT_EQ(coarse->depth_at(0), -1.0f);
}

TEST(ViewMeasurements, AnEmptyMapFromAGpuSweepKeepsNothing) {
    const SweepPlan plan = plan_of({64}, 1);
    ViewMeasurements store(plan);
    store.add(plan.views[0], DeviationMap{});
    EXPECT_EQ(store.find(0), nullptr);
}

TEST(MeasuredPixels, FollowTheViewThroughAResizeAndARoll) {
    const Mesh sphere = make_phantom({.kind = PhantomKind::Sphere});
    const View sweep = make_view(sphere, ViewSpec{.width = 64, .height = 64});
    const SweepPlan plan = plan_of({64}, 1);
    ViewMeasurements store(plan);
    PlannedView pv = plan.views[0];
    pv.view = sweep;
    store.add(pv, half_and_half(64, 64));
    const detail::MeasuredFloor floor{.normal = 20.0, .depth = 0.5};
    // Twice the size: the left half of the picture is the compared half.
    View big = make_view(sphere, ViewSpec{.width = 128, .height = 128});
    const auto px = detail::measured_pixels(*store.find(0), sweep, big, floor);
    EXPECT_FLOAT_EQ(px.depth[64 * 128 + 20], -1.0f);
    EXPECT_EQ(px.status[64 * 128 + 100], static_cast<std::uint8_t>(MeasuredStatus::ReferenceOnly));
    EXPECT_EQ(px.beyond[64 * 128 + 20], 1) << "|−1| beyond the depth floor 0.5";
    // Rolled a quarter turn about the viewing axis: the compared half is now above or below.
    View rolled = big;
    rolled.camera.world_from_camera.linear() =
        sweep.camera.world_from_camera.linear() *
        Eigen::AngleAxisd(0.5 * 3.14159265358979, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const auto r = detail::measured_pixels(*store.find(0), sweep, rolled, floor);
    const bool top = std::isfinite(r.depth[20 * 128 + 64]);
    const bool bottom = std::isfinite(r.depth[108 * 128 + 64]);
    EXPECT_NE(top, bottom) << "one of top and bottom is the compared half";
    EXPECT_FALSE(std::isfinite(r.depth[64 * 128 + 20]) && std::isfinite(r.depth[64 * 128 + 108]));
}

TEST(MeasuredPixels, EachViewMeasuresItsDepthFloorFromItsMajority) {
    const SweepPlan plan = plan_of({64}, 1);
    ViewMeasurements store(plan);
    DeviationMap d = half_and_half(64, 64);
    // Compared cells: depth ±0.01 alternating (the two tessellations' sag), one of them −1.
    for (std::size_t p = 0; p < d.signed_depth.size(); ++p)
        if (std::isfinite(d.signed_depth[p])) d.signed_depth[p] = p % 2 ? 0.01f : -0.01f;
    d.signed_depth[0] = -1.0f;
    store.add(plan.views[0], d);
    const double floor = detail::view_depth_floor(*store.find(0), 0.001, 6.0);
    EXPECT_NEAR(floor, 0.01, 1e-4) << "median 0.01, MAD 0: the noise's own level";
    EXPECT_DOUBLE_EQ(detail::view_depth_floor(*store.find(0), 0.05, 6.0), 0.05)
        << "never below the zoom's shape floor";
}

TEST(MeasuredPixels, BeyondTheDepthFloorWhenThereIsOneElseTheMetricFloor) {
    const detail::MeasuredFloor floor{.normal = 2.0, .depth = 0.1};
    EXPECT_TRUE(detail::beyond_floor(-0.2f, 1.0f, floor));
    EXPECT_FALSE(detail::beyond_floor(0.05f, 1.0f, floor));
    EXPECT_FALSE(detail::beyond_floor(0.0f, 3.0f, floor)) << "an angle alone is not shape";
    EXPECT_FALSE(detail::beyond_floor(kNaN, 3.0f, floor));
    const detail::MeasuredFloor normal_rule{.normal = 2.0, .depth = 0.0};
    EXPECT_TRUE(detail::beyond_floor(0.0f, 3.0f, normal_rule));
    EXPECT_FALSE(detail::beyond_floor(-0.2f, 1.0f, normal_rule))
        << "without a depth floor only the metric counts";
}

// A sphere (radius 10) with a 0.5-deep dent facing +x, swept at elevation 0 every 90°.
struct DentedSweep {
    // (named after the test that asks first: CTest runs each test in a process of its own, side
    // by side, and they must not share a folder)
    fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "view_pictures" /
                   ::testing::UnitTest::GetInstance()->current_test_info()->name();
    Mesh ref = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 4});
    AnalysisResult result;
    int facing = -1;    ///< the view looking at the dent
    int opposite = -1;  ///< the view from the other side

    DentedSweep() {
        fs::remove_all(dir);
        fs::create_directories(dir);
        Mesh exa = ref;
        apply_damage(
            exa, {DamageSpec{
                     .kind = DamageKind::Dent, .center = {10, 0, 0}, .radius = 3.0, .depth = 0.5}});
        InspectOptions o;
        o.analysis.fit.mode = FitMode::Identity;
        o.analysis.sweep.plan.azimuth_step_deg = 90;
        o.analysis.sweep.plan.elevations_deg = {0};
        o.analysis.sweep.plan.size = 128;
        o.analysis.sweep.render.backend = Backend::Embree;
        o.exports.output = dir / "out";
        o.exports.write_views = true;
        result = inspect(ref, exa, o, {}).analysis;
        for (const auto& pv : result.sweep.plan.views) {
            const double toward_dent = -pv.view.camera.forward().x();  // camera on +x: 1
            if (toward_dent > 0.99) facing = pv.view.index;
            if (toward_dent < -0.99) opposite = pv.view.index;
        }
    }
    [[nodiscard]] OIIO::ImageBuf picture(int view) const {
        const auto& v = result.sweep.plan.views[static_cast<std::size_t>(view)].view;
        OIIO::ImageBuf img((dir / "out" / "views" / (view_file_stem(v) + ".png")).string());
        EXPECT_TRUE(img.read()) << img.geterror();
        return img;
    }
};

const DentedSweep& dented() {
    static const DentedSweep sweep;
    return sweep;
}

TEST(ViewPictures, AViewFacingTheDentShowsBlueWhereItProjectsAndNowhereElse) {
    const DentedSweep& s = dented();
    ASSERT_GE(s.facing, 0);
    const OIIO::ImageBuf img = s.picture(s.facing);
    // The picture (384 px: 128-px views are drawn at least that large) below the title; the
    // view looks at the sphere's centre, so the dent lies at the picture's centre (any roll).
    const int size = img.spec().width - detail::kLegendWidth;
    ASSERT_EQ(size, 384);
    const double cx = size / 2.0, cy = detail::kTitleHeight + size / 2.0;
    // note: 384 px frame 2 × 1.05 × 17.3 (the bounding sphere): 10.6 px per unit, the dent's
    // radius of 3 is 32 px; its rim is shallow, so blue ends inside 50 px.
    int inside = 0, outside = 0;
    for (int y = detail::kTitleHeight; y < detail::kTitleHeight + size; ++y)
        for (int x = 0; x < size; ++x) {
            if (!is_blue(pixel(img, x, y))) continue;
            const double r = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
            if (r < 32) ++inside;
            if (r > 50) ++outside;
        }
    EXPECT_GT(inside, 1500) << "the dent is blue where it projects";
    EXPECT_EQ(outside, 0) << "unchanged surface shows no blue";
}

TEST(ViewPictures, AViewThatCannotSeeTheDentShowsNoBlue) {
    const DentedSweep& s = dented();
    ASSERT_GE(s.opposite, 0);
    const OIIO::ImageBuf img = s.picture(s.opposite);
    int blue = 0, surface = 0;
    for (int y = detail::kTitleHeight; y < img.spec().height; ++y)
        for (int x = 0; x < img.spec().width - detail::kLegendWidth; ++x) {
            const Rgb c = pixel(img, x, y);
            blue += is_blue(c);
            surface += c[0] > 0.5f;  // the pale, unchanged surface
        }
    EXPECT_EQ(blue, 0);
    EXPECT_GT(surface, 50000) << "the sphere is drawn";
}

TEST(ViewPictures, TheMosaicChartsWhichViewsSawTheDentAndDrawsThem) {
    const DentedSweep& s = dented();
    OIIO::ImageBuf img((s.dir / "out" / "mosaic_z0.png").string());
    ASSERT_TRUE(img.read()) << img.geterror();
    const auto& plan = s.result.sweep.plan;
    const auto cell_colour = [&](int view) {
        const auto& pv = plan.views[static_cast<std::size_t>(view)];
        const auto [x, y] = detail::chart_cell_origin(pv.step, pv.ring);
        return pixel(img, x + 4, detail::kTitleHeight + y + 14);  // left of the text and tag
    };
    const Rgb nothing = detail::chart_colour(0.0, 1.0);
    const Rgb behind = cell_colour(s.opposite);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(behind[k], nothing[k], 0.02f) << "0 % beyond";
    const Rgb saw = cell_colour(s.facing);
    EXPECT_GT(std::abs(saw[1] - nothing[1]), 0.1f) << "the view facing the dent measured it";
    // Below the chart, the region's best view drawn whole, with the dent in blue.
    ASSERT_EQ(s.result.decisions[0].regions.regions.size(), 1u);
    int blue = 0;
    for (int y = detail::kTitleHeight + 200; y < img.spec().height; ++y)
        for (int x = 0; x < img.spec().width - detail::kLegendWidth; ++x)
            blue += is_blue(pixel(img, x, y));
    EXPECT_GT(blue, 300);
    EXPECT_LT(img.spec().width * img.spec().height, 1400 * 1000) << "opens quickly";
}

TEST(ViewPictures, WithoutMeasurementsAViewShowsTheAtlasAndTheChartSaysNotAvailable) {
    // What a sweep that compared on the GPU leaves: no per-view pixels.
    const DentedSweep& s = dented();
    const fs::path target = s.dir / "atlas_only";
    fs::remove_all(target);
    {
        OutputFolder folder(target);
        ExportOptions exports;
        exports.write_views = true;
        (void)write_pictures(folder, s.ref, s.result, exports, Orientation{});
        folder.commit();
    }
    const auto& view = s.result.sweep.plan.views[static_cast<std::size_t>(s.facing)].view;
    OIIO::ImageBuf picture((target / "views" / (view_file_stem(view) + ".png")).string());
    ASSERT_TRUE(picture.read()) << picture.geterror();
    int blue = 0;
    for (int y = detail::kTitleHeight; y < picture.spec().height; ++y)
        for (int x = 0; x < picture.spec().width - detail::kLegendWidth; ++x)
            blue += is_blue(pixel(picture, x, y));
    EXPECT_GT(blue, 1500) << "the atlas's dent, seen from this view";
    OIIO::ImageBuf mosaic((target / "mosaic_z0.png").string());
    ASSERT_TRUE(mosaic.read()) << mosaic.geterror();
    const auto& pv = s.result.sweep.plan.views[static_cast<std::size_t>(s.opposite)];
    const auto [x, y] = detail::chart_cell_origin(pv.step, pv.ring);
    // Hatched grey, no share: two greys along the cell's top row, none of the map's colours.
    int grey = 0;
    for (int i = 0; i < 20; ++i) {
        const Rgb c = pixel(mosaic, x + i, detail::kTitleHeight + y + 2);
        grey += std::abs(c[0] - c[2]) < 0.02f && std::abs(c[0] - c[1]) < 0.02f && c[0] > 0.25f;
    }
    EXPECT_EQ(grey, 20);
}

TEST(ViewPictures, AViewIsDrawnFromWhatItMeasuredNotFromTheAtlas) {
    // The facing view "measured" a gain everywhere; the atlas holds the dent (a loss).
    const DentedSweep& s = dented();
    const auto& pv = s.result.sweep.plan.views[static_cast<std::size_t>(s.facing)];
    DeviationMap gain;
    gain.width = pv.view.camera.width;
    gain.height = pv.view.camera.height;
    const auto n = static_cast<std::size_t>(gain.width * gain.height);
    gain.signed_depth.assign(n, 0.5f);
    gain.angle_deg.assign(n, 10.0f);
    gain.silhouette.assign(n, 0);
    summarise(gain);
    ViewMeasurements measured(s.result.sweep.plan);
    measured.add(pv, gain);
    const fs::path target = s.dir / "measured_gain";
    fs::remove_all(target);
    {
        OutputFolder folder(target);
        ExportOptions exports;
        exports.write_views = true;
        (void)write_pictures(folder, s.ref, s.result, exports, Orientation{}, {}, {}, &measured);
        folder.commit();
    }
    OIIO::ImageBuf picture((target / "views" / (view_file_stem(pv.view) + ".png")).string());
    ASSERT_TRUE(picture.read()) << picture.geterror();
    int blue = 0, red = 0;
    for (int y = detail::kTitleHeight; y < picture.spec().height; ++y)
        for (int x = 0; x < picture.spec().width - detail::kLegendWidth; ++x) {
            const Rgb c = pixel(picture, x, y);
            blue += is_blue(c);
            red += c[0] > c[2] + 0.15f;
        }
    EXPECT_EQ(blue, 0) << "the atlas's dent is not what this view measured";
    EXPECT_GT(red, 50000) << "the whole surface in view measured a gain";
}

}  // namespace
}  // namespace glint
