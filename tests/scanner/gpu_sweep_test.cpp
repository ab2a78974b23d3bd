// The GPU path of the sweep (scanner/gpu_sweep.h, render/gpu_atlas.h) against the read-back
// path on the same device (lavapipe here): the same atlas, view numbers and decisions, within
// the tolerances below. Each names what it covers and why it is not zero:
//
// - counts, best/max views, seen vertices, view pixel counts: exact. Both paths make the same
//   observations (same float/double operations in the same order, no fused multiply-add).
// - a pixel's angle, hence the max, a view's max angle and a mean's inputs: kAngleUlps float
//   ulps. The device's acos is a series in double within 2 ulp of libm's, so a float angle
//   can land one ulp away (measured on lavapipe: 0 ulp in every test here; the test prints it).
// - per-vertex means (value, missing share, signed depth): kMeanTolerance (of the metric's
//   range; of one mesh unit for depth). The sums are 64-bit fixed point (each observation
//   rounded to 2^-k, k ≥ 37 here) where the CPU rounds double sums; measured on lavapipe:
//   ≤ 1.2e-13 for the means of the metric, ≤ 5e-10 for the signed depth, 0 for the weights.
// - a view's mean angle: its fixed-point sum has a step of 2^-(54 − log2 pixels) degrees.
// Each comparison runs with the graphics pipeline's frames and again with the compute
// rasteriser's (render/context.h Raster): both paths then see the same frames, so the same
// tolerances hold.
#include "scanner/gpu_sweep.h"

#include "scanner/sweep.h"

#include "mesh/cancel.h"
#include "mesh/damage.h"
#include "mesh/error.h"
#include "mesh/phantom.h"
#include "render/gpu_atlas.h"
#include "tests/scanner/dented_pair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>

namespace glint {
namespace {

constexpr int kAngleUlps = 1;
constexpr double kMeanTolerance = 1e-6;

std::int64_t ulps(float a, float b) {
    std::int32_t ia = 0, ib = 0;
    std::memcpy(&ia, &a, 4);
    std::memcpy(&ib, &b, 4);
    return std::abs(static_cast<std::int64_t>(ia) - ib);
}

bool same_or_both_nan(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

/// Largest differences between two atlases of one mesh, and how many vertices differ in the
/// exactly-compared fields.
struct AtlasDifference {
    std::size_t count = 0, best_view = 0, max_view = 0, depth_at_max = 0;
    std::int64_t max_ulps = 0, best_cos_ulps = 0;
    double mean = 0, weight = 0, missing = 0, depth_mean = 0;
};

AtlasDifference difference(const ZoomAtlas& a, const ZoomAtlas& b) {
    AtlasDifference d;
    for (std::size_t v = 0; v < a.count.size(); ++v) {
        d.count += a.count[v] != b.count[v];
        d.best_view += a.best_view[v] != b.best_view[v];
        d.max_view += a.max_view[v] != b.max_view[v];
        d.depth_at_max += !same_or_both_nan(a.depth_at_max[v], b.depth_at_max[v]);
        d.max_ulps = std::max(d.max_ulps, ulps(a.value_max[v], b.value_max[v]));
        d.best_cos_ulps = std::max(d.best_cos_ulps, ulps(a.best_cos[v], b.best_cos[v]));
        d.mean = std::max(d.mean, std::abs(double(a.value_mean[v]) - b.value_mean[v]));
        d.weight = std::max(d.weight, std::abs(double(a.weight[v]) - b.weight[v]) /
                                          std::max(1.0, double(a.weight[v])));
        d.missing = std::max(d.missing, std::abs(double(a.missing[v]) - b.missing[v]));
        if (std::isnan(a.depth_mean[v]) != std::isnan(b.depth_mean[v])) {
            d.depth_mean = std::numeric_limits<double>::infinity();
        } else if (!std::isnan(a.depth_mean[v])) {
            d.depth_mean =
                std::max(d.depth_mean, std::abs(double(a.depth_mean[v]) - b.depth_mean[v]));
        }
    }
    return d;
}

/// Expects the GPU sweep to equal the read-back sweep within the file's tolerances.
void expect_same_sweep(const SweepResult& host, const SweepResult& gpu, double metric_range,
                       const char* what) {
    ASSERT_FALSE(host.on_gpu) << what;
    ASSERT_TRUE(gpu.on_gpu) << what << ": " << gpu.accumulation_note;
    ASSERT_EQ(host.zooms.size(), gpu.zooms.size());
    ASSERT_EQ(host.views.size(), gpu.views.size());
    for (std::size_t i = 0; i < host.views.size(); ++i) {
        const ViewSummary& h = host.views[i];
        const ViewSummary& g = gpu.views[i];
        EXPECT_EQ(h.index, g.index);
        EXPECT_EQ(h.reference_pixels, g.reference_pixels) << what << " view " << i;
        EXPECT_EQ(h.compared, g.compared) << what << " view " << i;
        EXPECT_EQ(h.reference_only, g.reference_only) << what << " view " << i;
        EXPECT_EQ(h.examined_only, g.examined_only) << what << " view " << i;
        EXPECT_LE(ulps(float(h.max_angle_deg), float(g.max_angle_deg)), kAngleUlps)
            << what << " view " << i;
        EXPECT_NEAR(h.mean_angle_deg, g.mean_angle_deg, 1e-9 * std::max(1.0, h.mean_angle_deg))
            << what << " view " << i;
    }
    for (std::size_t z = 0; z < host.zooms.size(); ++z) {
        const ZoomAtlas& a = host.zooms[z].atlas;
        const ZoomAtlas& b = gpu.zooms[z].atlas;
        const AtlasDifference d = difference(a, b);
        std::cout << what << " zoom " << z << ": " << a.count.size()
                  << " vertices; differing count " << d.count << ", best_view " << d.best_view
                  << ", max_view " << d.max_view << ", depth_at_max " << d.depth_at_max << "; max "
                  << d.max_ulps << " ulp, best_cos " << d.best_cos_ulps << " ulp; |Δ| mean "
                  << d.mean << ", weight (rel) " << d.weight << ", missing " << d.missing
                  << ", depth_mean " << d.depth_mean << "\n";
        EXPECT_EQ(d.count, 0u) << what;
        EXPECT_EQ(d.best_view, 0u) << what;
        EXPECT_EQ(d.max_view, 0u) << what;
        EXPECT_EQ(d.depth_at_max, 0u) << what;
        EXPECT_LE(d.max_ulps, kAngleUlps) << what;
        EXPECT_EQ(d.best_cos_ulps, 0) << what;
        EXPECT_LE(d.mean, kMeanTolerance * metric_range) << what;
        EXPECT_LE(d.weight, kMeanTolerance) << what;
        EXPECT_LE(d.missing, kMeanTolerance) << what;
        EXPECT_LE(d.depth_mean, kMeanTolerance) << what;
        EXPECT_EQ(host.zooms[z].coverage.seen, gpu.zooms[z].coverage.seen) << what;
    }
}

void expect_same_on_a_dented_phantom(Raster raster) {
    const test::DentedPair& p = test::dented_pair();
    SweepOptions host = test::small_vulkan_sweep(Accumulation::Host, raster);
    const SweepPlan plan = make_sweep_plan(p.reference, host.plan);
    const SweepResult h = run_sweep(p.reference, p.examined, plan, host);
    const SweepResult g = run_sweep(p.reference, p.examined, plan,
                                    test::small_vulkan_sweep(Accumulation::Gpu, raster));
    expect_same_sweep(h, g, 180.0, "angle, ortho, s=2, 96²");
    // Not trivially equal: the dent deviates, and most of the surface was observed.
    EXPECT_GT(
        *std::max_element(g.zooms[0].atlas.value_max.begin(), g.zooms[0].atlas.value_max.end()),
        5.0f);
    EXPECT_GT(g.zooms[0].coverage.fraction, 0.8);
}

TEST(GpuSweep, GivesTheReadBackAtlasOnADentedPhantom) {
    expect_same_on_a_dented_phantom(Raster::Auto);
}

/// The plan's views as perspective cameras at two zooms (footprint halved at the second).
SweepPlan perspective_plan(const Mesh& mesh, int size) {
    SweepPlan plan;
    plan.radius = framing_sphere(mesh).radius * 1.05;
    plan.footprints = {0.0, 0.0};
    int index = 0;
    for (int zoom = 0; zoom < 2; ++zoom) {
        for (double az : {20.0, 140.0, 260.0}) {
            for (double el : {-40.0, 35.0}) {
                const ViewSpec spec{.azimuth_deg = az,
                                    .elevation_deg = el,
                                    .zoom = zoom == 0 ? ZoomKind::Fit : ZoomKind::DistancePixels,
                                    .zoom_value = 3.0 * size,
                                    .width = size,
                                    .height = size,
                                    .projection = Projection::Perspective,
                                    .fov_y_rad = 0.6,
                                    .zoom_index = zoom,
                                    .index = index++};
                plan.views.push_back(PlannedView{.view = make_view(mesh, spec)});
            }
        }
    }
    plan.footprints = {plan.views.front().view.footprint, plan.views.back().view.footprint};
    plan.sizes = {size, size};
    return plan;
}

void expect_same_for_perspective_views_rgb_and_a_mask(Raster raster) {
    const test::DentedPair& p = test::dented_pair();
    SweepOptions host = test::small_vulkan_sweep(Accumulation::Host, raster);
    host.metric = Metric::RgbAbs;
    host.render.supersample = 1;
    host.render.min_coverage = 0.5f;  // the frame mask (render/renderer.cpp finish_frame)
    host.compare.min_coverage = 0.5f;
    SweepOptions gpu = host;
    gpu.accumulate = Accumulation::Gpu;
    const SweepPlan plan = perspective_plan(p.reference, 80);
    const SweepResult h = run_sweep(p.reference, p.examined, plan, host);
    const SweepResult g = run_sweep(p.reference, p.examined, plan, gpu);
    expect_same_sweep(h, g, 255.0, "rgb, perspective, s=1, two zooms, 80²");
    EXPECT_GT(
        *std::max_element(g.zooms[1].atlas.value_max.begin(), g.zooms[1].atlas.value_max.end()),
        10.0f);
}

TEST(GpuSweep, GivesTheReadBackAtlasForPerspectiveViewsTheRgbMetricAndACoverageMask) {
    expect_same_for_perspective_views_rgb_and_a_mask(Raster::Auto);
}

/// The examined surface without its end beyond x = `cut` (an open mesh): from the side, the
/// reference shows surface there and the examined none (missing surface).
Mesh cut_off(const Mesh& m, float cut) {
    Mesh out;
    out.positions = m.positions;
    out.normals = m.normals;
    for (const auto& t : m.triangles)
        if (m.positions[t[0]].x() < cut && m.positions[t[1]].x() < cut &&
            m.positions[t[2]].x() < cut)
            out.triangles.push_back(t);
    return out;
}

void expect_same_where_the_examined_surface_is_missing(Raster raster) {
    const test::DentedPair& p = test::dented_pair();
    const Mesh examined = cut_off(p.examined, 7.0f);
    SweepOptions host = test::small_vulkan_sweep(Accumulation::Host, raster);
    host.render.supersample = 3;
    SweepOptions gpu = host;
    gpu.accumulate = Accumulation::Gpu;
    const SweepPlan plan = make_sweep_plan(p.reference, host.plan);
    const SweepResult h = run_sweep(p.reference, examined, plan, host);
    const SweepResult g = run_sweep(p.reference, examined, plan, gpu);
    std::size_t reference_only = 0;
    for (const auto& v : g.views) reference_only += v.reference_only;
    EXPECT_GT(reference_only, 100u);  // the hole shows
    expect_same_sweep(h, g, 180.0, "angle, missing surface, s=3, 96²");
    EXPECT_GT(*std::max_element(g.zooms[0].atlas.missing.begin(), g.zooms[0].atlas.missing.end()),
              0.5f);
}

TEST(GpuSweep, GivesTheReadBackAtlasWhereTheExaminedSurfaceIsMissing) {
    expect_same_where_the_examined_surface_is_missing(Raster::Auto);
}

TEST(GpuSweep, GivesTheReadBackAtlasWithTheComputeRasteriser) {
    expect_same_on_a_dented_phantom(Raster::Compute);
    expect_same_for_perspective_views_rgb_and_a_mask(Raster::Compute);
    expect_same_where_the_examined_surface_is_missing(Raster::Compute);
}

TEST(GpuSweep, FallsBackToTheReadBackPathOnEmbreeAndSaysWhy) {
    const test::DentedPair& p = test::dented_pair();
    SweepOptions o = test::small_vulkan_sweep(Accumulation::Auto);
    o.render.backend = Backend::Embree;
    o.render.device.clear();
    o.plan.elevations_deg = {30};
    const SweepPlan plan = make_sweep_plan(p.reference, o.plan);
    const SweepResult r = run_sweep(p.reference, p.examined, plan, o);
    EXPECT_FALSE(r.on_gpu);
    EXPECT_NE(r.accumulation_note.find("Vulkan"), std::string::npos) << r.accumulation_note;
    o.accumulate = Accumulation::Gpu;
    EXPECT_THROW(static_cast<void>(run_sweep(p.reference, p.examined, plan, o)), DeviceError);
}

TEST(GpuSweep, ObserverSeesEveryViewInOrderWithoutFramesAndCanStopTheSweep) {
    const test::DentedPair& p = test::dented_pair();
    SweepOptions o = test::small_vulkan_sweep(Accumulation::Gpu);
    o.plan.size = 64;
    const SweepPlan plan = make_sweep_plan(p.reference, o.plan);
    std::vector<int> seen;
    const SweepResult r = run_sweep(p.reference, p.examined, plan, o,
                                    [&](const PlannedView& v, const DeviationMap& d) {
                                        EXPECT_EQ(d.value.size() + d.angle_deg.size(), 0u);
                                        seen.push_back(v.view.index);
                                    });
    ASSERT_EQ(seen.size(), plan.views.size());
    for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], plan.views[i].view.index);
    // An observer that stops the run after three views: the error propagates, and the next
    // sweep on the same device gives the same atlas as before.
    int calls = 0;
    EXPECT_THROW(static_cast<void>(run_sweep(p.reference, p.examined, plan, o,
                                             [&](const PlannedView&, const DeviationMap&) {
                                                 if (++calls == 3)
                                                     throw Cancelled("stopped by the test");
                                             })),
                 Cancelled);
    EXPECT_EQ(calls, 3);
    const SweepResult again = run_sweep(p.reference, p.examined, plan, o);
    EXPECT_EQ(again.zooms[0].atlas.count, r.zooms[0].atlas.count);
    EXPECT_EQ(again.zooms[0].atlas.value_mean, r.zooms[0].atlas.value_mean);
}

}  // namespace
}  // namespace glint
