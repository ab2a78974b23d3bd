// Views per second of the sweep's per-view work on Vulkan, two ways side by side (issue 13):
//   read-back  render both frames, read them back, resolve, compare and back-project on the CPU
//              (render_view_pairs + compare_frames + backproject_view: the sweep's Host path);
//   gpu        the same on the device (GpuAtlas::run + read_totals: the sweep's GPU path).
// Run: tools/bench gpu (lavapipe here; on a GPU machine the GPU is picked, or name it:
// GLINT_DEVICE=NVIDIA).
//
// The pair: the bumpy sphere of bench/render_bench.cpp at 100k and 1M triangles as the
// reference, the same surface tessellated ~10 % finer with a dent as the examined mesh, both on
// one shared context. A ring of 16 views, orthographic, framed to fit, s = 1 (the render
// benchmark's setting), at 512² and 1024². BM_GpuVsReadBack times both paths alternately inside
// each iteration, so they share the machine's state; its counters: readback_views_per_s,
// gpu_views_per_s, speedup = gpu / read-back, and the GPU path's device time per view by stage
// from timestamps: dev_render_ms (both normal passes), dev_pixels_ms (resolve, compare,
// scatter), dev_vertices_ms (gather, fold) (tools/bench prints the medians). Renderer and
// atlas creation (mesh upload, buffers, pipelines) is not timed; the GPU path's per-sweep
// read-back of the per-vertex totals is, once per 16 views (a real sweep has 60 or more).
#include "bench/bumpy_sphere.h"
#include "mesh/damage.h"
#include "mesh/normals.h"
#include "render/context.h"
#include "render/gpu_atlas.h"
#include "render/renderer.h"
#include "render/view.h"
#include "scanner/atlas.h"
#include "scanner/backproject.h"
#include "scanner/metric.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>

namespace glint {
namespace {

struct Setup {
    Mesh reference;
    Mesh examined;
    std::unique_ptr<Renderer> reference_renderer;
    std::unique_ptr<Renderer> examined_renderer;
    std::unique_ptr<GpuAtlas> atlas;
};

/// One setup per mesh size on the process's Vulkan context; creation not timed.
Setup& setup(int kilo_triangles) {
    static std::map<int, Setup> cache;
    auto [it, inserted] = cache.try_emplace(kilo_triangles);
    Setup& s = it->second;
    if (inserted) {
        // 4·r² ≈ triangles: r = 158 → 99.5k, r = 500 → 998k; the examined mesh 5 % more rings.
        const int rings = kilo_triangles >= 1000 ? 500 : 158;
        s.reference = bench::bumpy_sphere(rings);
        s.examined = bench::bumpy_sphere(rings * 21 / 20);
        apply_damage(s.examined, {DamageSpec{.kind = DamageKind::Dent,
                                             .center = {0.0, 1.0, 0.3},
                                             .radius = 0.25,
                                             .depth = 0.02}});
        const auto context = shared_render_context(ContextOptions{.backend = Backend::Vulkan});
        s.reference_renderer =
            std::make_unique<Renderer>(context, s.reference, FrameOptions{.supersample = 1});
        s.examined_renderer =
            std::make_unique<Renderer>(context, s.examined, FrameOptions{.supersample = 1});
        if (GpuAtlas::supported(*s.reference_renderer, *s.examined_renderer, {}))
            s.atlas = std::make_unique<GpuAtlas>(
                *s.reference_renderer, *s.examined_renderer,
                GpuAtlasOptions{.framed_radius = framing_sphere(s.reference).radius});
    }
    return s;
}

/// The sweep's read-back path for one zoom (frames read back, compared, scattered and folded
/// on the host; one frame pair at a time, whole); returns the compared pixels.
std::size_t run_read_back(Setup& s, const std::vector<View>& views) {
    AtlasAccumulator atlas(s.reference, views.front().footprint);
    const BackprojectOptions bp{.framed_radius = framing_sphere(s.reference).radius};
    const MetricDescriptor& metric = describe(Metric::AngleDeg);
    BackprojectScratch scratch;
    ViewMaps maps;
    std::vector<AtlasSample> samples;
    std::size_t compared = 0;
    render_view_pairs(
        *s.reference_renderer, *s.examined_renderer, views,
        [&](std::size_t i, const Frame& reference, const Frame& examined) {
            const FrameView rv = frame_view(reference), ev = frame_view(examined);
            maps.resize(reference.width, reference.height);
            maps.deviation = compare_frames(rv, ev);
            maps.deviation.value.resize(maps.deviation.angle_deg.size());
            metric.compute(rv, ev, maps.deviation.angle_deg, maps.deviation.value);
            const FrameRows rows = frame_rows(reference, 0, reference.height);
            record_reference_rows(rows, bp.min_coverage, maps);
            samples.clear();
            static_cast<void>(scatter_rows(s.reference, views[i], rows, maps, bp, samples));
            const std::vector<AtlasSample>* bands[] = {&samples};
            fold_view(s.reference, views[i], bands, maps, bp, atlas, scratch, 0);
            compared += maps.deviation.compared;
        });
    benchmark::DoNotOptimize(atlas.finish());
    return compared;
}

/// The sweep's GPU path; returns the compared pixels.
std::size_t run_gpu(Setup& s, const std::vector<View>& views) {
    std::size_t compared = 0;
    s.atlas->run(views,
                 [&](std::size_t, const ViewNumbers& summary) { compared += summary.compared; });
    benchmark::DoNotOptimize(s.atlas->read_totals());
    return compared;
}

void BM_GpuVsReadBack(benchmark::State& state) {
    using Clock = std::chrono::steady_clock;
    const int kilo = static_cast<int>(state.range(0));
    const int size = static_cast<int>(state.range(1));
    Setup& s = setup(kilo);
    if (!s.atlas) {
        state.SkipWithError("the Vulkan device cannot run the GPU atlas (see glint devices)");
        return;
    }
    const std::vector<View> views = bench::ring_views(s.reference, size, 16);
    double read_back_s = 0.0;
    double gpu_s = 0.0;
    std::size_t compared_read_back = 0;
    std::size_t compared_gpu = 0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        compared_read_back += run_read_back(s, views);
        const auto t1 = Clock::now();
        compared_gpu += run_gpu(s, views);
        const auto t2 = Clock::now();
        read_back_s += std::chrono::duration<double>(t1 - t0).count();
        gpu_s += std::chrono::duration<double>(t2 - t1).count();
    }
    if (compared_read_back != compared_gpu)
        state.SkipWithError("the two paths compared different pixels");
    const double views_run = static_cast<double>(views.size() * state.iterations());
    state.counters["readback_views_per_s"] = read_back_s > 0.0 ? views_run / read_back_s : 0.0;
    state.counters["gpu_views_per_s"] = gpu_s > 0.0 ? views_run / gpu_s : 0.0;
    state.counters["speedup"] = gpu_s > 0.0 ? read_back_s / gpu_s : 0.0;
    // Where the device spends a view of the GPU path (timestamps; the last iteration's run).
    const GpuAtlasTimings& t = s.atlas->timings();
    if (t.measured && t.views > 0) {
        const double per_view_ms = 1e3 / static_cast<double>(t.views);
        state.counters["dev_render_ms"] = t.render_s * per_view_ms;
        state.counters["dev_pixels_ms"] = t.pixels_s * per_view_ms;
        state.counters["dev_vertices_ms"] = t.vertices_s * per_view_ms;
    }
    state.SetLabel(std::to_string(s.reference.triangle_count()) + " tri " + std::to_string(size) +
                   "² s=1 | " + s.reference_renderer->info().device_name);
}

BENCHMARK(BM_GpuVsReadBack)
    ->ArgsProduct({{100, 1000}, {512, 1024}})
    ->ArgNames({"ktri", "size"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

}  // namespace
}  // namespace glint
