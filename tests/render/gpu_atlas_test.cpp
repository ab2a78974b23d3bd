// The GPU atlas on its own (render/gpu_atlas.h), with the validation layer's synchronisation
// checks on: what it accumulates for surfaces whose deviation is known in closed form. Its
// agreement with the CPU read-back path is tests/scanner/gpu_sweep_test.cpp's.
#include "render/gpu_atlas.h"

#include "mesh/error.h"
#include "render/context.h"
#include "render/view.h"
#include "render_test_util.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {
namespace {

using test::expect_no_validation_messages;

std::shared_ptr<RenderContext> validated_context() {
    return shared_render_context(ContextOptions{.backend = Backend::Vulkan, .validation = true});
}

std::vector<View> ring(const Mesh& mesh, int size, int count, int zoom = 0) {
    std::vector<View> views;
    for (int i = 0; i < count; ++i) {
        views.push_back(make_view(mesh, ViewSpec{.azimuth_deg = 360.0 * i / count,
                                                 .elevation_deg = i % 2 ? 25.0 : -25.0,
                                                 .width = size,
                                                 .height = size,
                                                 .zoom_index = zoom,
                                                 .index = i}));
    }
    return views;
}

/// A copy of `mesh` with every vertex normal turned by `deg` about the x axis.
Mesh with_turned_normals(const Mesh& mesh, double deg) {
    Mesh m = mesh;
    const Eigen::Matrix3f turn =
        Eigen::AngleAxisf(static_cast<float>(deg * std::numbers::pi / 180.0),
                          Eigen::Vector3f::UnitX())
            .toRotationMatrix();
    for (auto& n : m.normals) n = (turn * n).normalized();
    return m;
}

TEST(GpuAtlas, FindsNoDeviationBetweenASurfaceAndItself) {
    const auto context = validated_context();
    const Mesh sphere = test::make_icosphere(3);
    Renderer a(context, sphere, FrameOptions{.supersample = 2});
    Renderer b(context, sphere, FrameOptions{.supersample = 2});
    GpuAtlas atlas(a, b, GpuAtlasOptions{.framed_radius = 1.0});
    const std::vector<View> views = ring(sphere, 48, 6);
    std::size_t calls = 0;
    atlas.run(views, [&](std::size_t i, const ViewNumbers& s) {
        EXPECT_EQ(i, calls++);
        EXPECT_GT(s.reference_pixels, 400u);  // the framed sphere is ~26 pixels across
        EXPECT_EQ(s.compared, s.reference_pixels);
        EXPECT_EQ(s.reference_only + s.examined_only, 0u);
        // Identical float normals: the angle is acos of a cosine within an ulp or so of 1.
        EXPECT_LT(s.max_angle_deg, 1e-4);
    });
    EXPECT_EQ(calls, views.size());
    // Device time by stage, when the queue writes timestamps (lavapipe does).
    const GpuAtlasTimings& timings = atlas.timings();
    if (timings.measured) {
        EXPECT_EQ(timings.views, views.size());
        EXPECT_GT(timings.render_s, 0.0);
        EXPECT_GT(timings.pixels_s, 0.0);
        EXPECT_GE(timings.vertices_s, 0.0);
    }
    const std::vector<AtlasTotals> totals = atlas.read_totals();
    ASSERT_EQ(totals.size(), 1u);
    const AtlasTotals& t = totals[0];
    std::size_t seen = 0;
    for (std::size_t v = 0; v < sphere.vertex_count(); ++v) {
        if (t.count[v] == 0) continue;
        ++seen;
        EXPECT_LT(t.value_max[v], 1e-4f);
        EXPECT_LT(t.value_sum[v], 1e-4 * t.weight[v]);
        EXPECT_EQ(t.missing_weight[v], 0.0);
        EXPECT_EQ(t.depth_sum[v], 0.0);
        EXPECT_GT(t.weight[v], 0.0);
        EXPECT_GE(t.best_view[v], 0);
        EXPECT_GT(t.best_cos[v], 0.2588f);
    }
    EXPECT_GT(seen, sphere.vertex_count() * 9 / 10);
    expect_no_validation_messages(a);
}

TEST(GpuAtlas, MeasuresNormalsTurnedByAKnownAngle) {
    const auto context = validated_context();
    // A flat square with normals +z, and the same square with every normal tilted by 12°:
    // every compared pixel deviates by exactly 12° (a constant normal interpolates to itself).
    const Mesh plane = test::make_corrugated_plane(24, 1.0, 0.0, 1.0);
    Mesh tilted = plane;
    const float tilt = static_cast<float>(12.0 * std::numbers::pi / 180.0);
    for (auto& n : tilted.normals) n = Vec3f(0.0f, std::sin(tilt), std::cos(tilt));
    Renderer a(context, plane, FrameOptions{.supersample = 2});
    Renderer b(context, tilted, FrameOptions{.supersample = 2});
    GpuAtlas atlas(a, b, GpuAtlasOptions{.framed_radius = 1.5});
    std::vector<View> views;
    for (int i = 0; i < 4; ++i)
        views.push_back(make_view(plane, ViewSpec{.azimuth_deg = 90.0 * i,
                                                  .elevation_deg = i % 2 ? 40.0 : 70.0,
                                                  .width = 48,
                                                  .height = 48,
                                                  .index = i}));
    atlas.run(views, [&](std::size_t, const ViewNumbers& s) {
        EXPECT_GT(s.compared, 500u);
        EXPECT_EQ(s.reference_only + s.examined_only, 0u);
        EXPECT_NEAR(s.mean_angle_deg, 12.0, 1e-4);
        EXPECT_NEAR(s.max_angle_deg, 12.0, 1e-4);
    });
    const AtlasTotals t = atlas.read_totals()[0];
    std::size_t seen = 0;
    for (std::size_t v = 0; v < plane.vertex_count(); ++v) {
        if (!(t.weight[v] > 0.0)) continue;
        ++seen;
        EXPECT_NEAR(t.value_sum[v] / t.weight[v], 12.0, 1e-4);
        // The maximum goes only to the vertex nearest a pixel (atlas.h): not every seen one.
        if (t.max_view[v] >= 0) {
            EXPECT_NEAR(t.value_max[v], 12.0f, 1e-4f);
        }
        EXPECT_EQ(t.missing_weight[v], 0.0);
        EXPECT_EQ(t.depth_sum[v], 0.0);  // the same surface: no depth difference
    }
    EXPECT_GT(seen, plane.vertex_count() * 9 / 10);
    expect_no_validation_messages(a);
}

TEST(GpuAtlas, MeasuresAnOutwardShiftAndTheRimItAdds) {
    const auto context = validated_context();
    const Mesh sphere = test::make_icosphere(3);
    // The examined sphere 10 % larger: nearer the camera (positive signed depth) and wider
    // (pixels only it covers, none only the reference covers).
    Mesh examined = sphere;
    for (auto& p : examined.positions) p *= 1.1f;
    Renderer a(context, sphere, FrameOptions{.supersample = 1});
    Renderer b(context, examined, FrameOptions{.supersample = 1});
    GpuAtlas atlas(a, b, GpuAtlasOptions{.framed_radius = 1.1});
    std::size_t examined_only = 0;
    atlas.run(ring(examined, 64, 4), [&](std::size_t, const ViewNumbers& s) {
        examined_only += s.examined_only;
        EXPECT_EQ(s.reference_only, 0u);
    });
    EXPECT_GT(examined_only, 100u);
    const AtlasTotals t = atlas.read_totals()[0];
    std::size_t seen = 0;
    for (std::size_t v = 0; v < sphere.vertex_count(); ++v) {
        if (!(t.depth_weight[v] > 0.0)) continue;
        ++seen;
        // The shells are 0.1 apart along the normal (a little less through a flat facet);
        // seen along a ray at incidence up to 75°, the depth difference lies between that and
        // 0.1 / cos 75°.
        const double depth = t.depth_sum[v] / t.depth_weight[v];
        EXPECT_GT(depth, 0.095);
        EXPECT_LT(depth, 0.1 / std::cos(75.0 * std::numbers::pi / 180.0));
    }
    EXPECT_GT(seen, sphere.vertex_count() / 2);
    expect_no_validation_messages(a);
}

TEST(GpuAtlas, RunsAgainFromClearedTotalsAndKeepsZoomsApart) {
    const auto context = validated_context();
    const Mesh sphere = test::make_icosphere(2);
    const Mesh turned = with_turned_normals(sphere, 5.0);
    Renderer a(context, sphere, FrameOptions{.supersample = 2});
    Renderer b(context, turned, FrameOptions{.supersample = 2});
    GpuAtlas atlas(a, b, GpuAtlasOptions{.framed_radius = 1.0, .zoom_count = 2});
    const std::vector<View> views = ring(sphere, 40, 4, 1);  // zoom 1 only
    atlas.run(views);
    const std::vector<AtlasTotals> first = atlas.read_totals();
    atlas.run(views);
    const std::vector<AtlasTotals> second = atlas.read_totals();
    ASSERT_EQ(first.size(), 2u);
    EXPECT_EQ(first[1].count, second[1].count);
    EXPECT_EQ(first[1].value_sum, second[1].value_sum);
    EXPECT_EQ(first[1].max_view, second[1].max_view);
    for (std::size_t v = 0; v < sphere.vertex_count(); ++v) {
        EXPECT_EQ(first[0].count[v], 0u);
        EXPECT_EQ(first[0].best_view[v], -1);
        EXPECT_EQ(first[0].max_view[v], -1);
    }
    EXPECT_GT(*std::max_element(first[1].count.begin(), first[1].count.end()), 0u);
    expect_no_validation_messages(a);
}

TEST(GpuAtlas, RefusesWhatItCannotDo) {
    const Mesh sphere = test::make_icosphere(1);
    const auto embree = shared_render_context(ContextOptions{.backend = Backend::Embree});
    Renderer ea(embree, sphere), eb(embree, sphere);
    std::string why;
    EXPECT_FALSE(GpuAtlas::supported(ea, eb, {}, &why));
    EXPECT_NE(why.find("Vulkan"), std::string::npos) << why;
    EXPECT_THROW(GpuAtlas(ea, eb, {}), InputError);

    const auto vk = validated_context();
    Renderer va(vk, sphere), vb(vk, sphere);
    Renderer view_space(vk, sphere, FrameOptions{.normal_space = NormalSpace::View});
    EXPECT_FALSE(GpuAtlas::supported(va, view_space, {}, &why));
    // A metric without a kernel is refused by name, never folded as another metric.
    EXPECT_TRUE(has_gpu_kernel(Metric::AngleDeg) && has_gpu_kernel(Metric::RgbAbs));
    const auto unknown = static_cast<Metric>(99);
    EXPECT_FALSE(has_gpu_kernel(unknown));
    EXPECT_FALSE(GpuAtlas::supported(va, vb, GpuAtlasOptions{.metric = unknown}, &why));
    EXPECT_NE(why.find("no GPU kernel"), std::string::npos) << why;
    EXPECT_THROW(GpuAtlas(va, vb, GpuAtlasOptions{.missing_value = -1.0f}), OptionError);
    GpuAtlas atlas(va, vb, {});
    EXPECT_THROW(atlas.run(ring(sphere, 16, 1, 3)), InputError);  // zoom 3 of 1
    expect_no_validation_messages(va);
}

}  // namespace
}  // namespace glint
