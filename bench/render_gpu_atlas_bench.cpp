// Views per second of the GPU atlas alone (render/gpu_atlas.h), and where the device spends a
// view (issue 25: ≥ 1000 views/s at 1M triangles, 1024², with the read-back no longer the bound).
// bench/gpu_atlas_bench.cpp times the same path beside the read-back path, and so links every
// glint library; this program links only glint_render (no OpenImageIO, VTK or ITK), so it and
// the few libraries it needs (Vulkan loader, Embree, TBB, Google Benchmark) can be carried to a
// GPU machine and run there against its driver:
//   GLINT_DEVICE=NVIDIA build/default/bench/glint_bench_render_gpu_atlas
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true   (one command line)
//
// The pair of bench/gpu_atlas_bench.cpp: the bumpy sphere at 100k and 1M triangles as the
// reference, the same surface tessellated 5 % finer with a dent as the examined mesh, both on
// one shared context, angle metric; each size with both rasterisers of the normal pass
// (render/context.h Raster: raster 0 the graphics pipeline, 1 the compute passes), side by side
// in one process. A sweep here is 60 views (the sweep's default count; 8 on a CPU device) on a
// ring around the mesh, orthographic, framed to fit, s = 1, at 512² and 1024² (and s = 2 at 1024² as one more
// row), followed by the read-back of the per-vertex totals, as a real sweep ends. Renderer and atlas creation (mesh upload, buffers, pipelines) is not timed.
//
// Counters (tools/bench prints the medians):
//   views_per_s      views over the wall time of run() + read_totals();
//   run_views_per_s  views over the wall time of run() alone (the per-view work);
//   totals_ms        read_totals() once per sweep: totals_copy_ms (device copy over the bus to
//                    the host, submit to fence) + totals_convert_ms (into AtlasTotals);
//   dev_render_ms, dev_pixels_ms, dev_vertices_ms   device time per view by stage
//                    (GpuAtlasTimings; the last iteration's sweep);
//   dev_busy         the device's share of run()'s wall time: the stages' sum over the wall
//                    time (near 1: the device bounds the rate; well below: the host does);
//   host_wait_us, host_work_us   per view, the host's time waiting for fences and the rest
//                    (parameters, recording, submission, timestamps).
// One row runs with 4 views in flight (GpuAtlasOptions::in_flight; 2 otherwise): measured on
// the H100 no faster than 2 (the host waits most of each view).
// Per view only the 32-byte summary crosses the bus (GpuAtlas::run); the totals once per sweep.
#include "bench/bumpy_sphere.h"
#include "mesh/damage.h"
#include "mesh/geometry.h"
#include "render/context.h"
#include "render/gpu_atlas.h"
#include "render/renderer.h"
#include "render/view.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <memory>
#include <tuple>
#include <utility>

namespace glint {
namespace {

struct Setup {
    Mesh reference;
    Mesh examined;
    std::unique_ptr<Renderer> reference_renderer;
    std::unique_ptr<Renderer> examined_renderer;
    std::unique_ptr<GpuAtlas> atlas;
    std::string why;  // when the atlas cannot run
};

/// One setup per (mesh size, supersample, raster, views in flight) on the process's Vulkan
/// context for that raster; creation not timed.
Setup& setup(int kilo_triangles, int supersample, Raster raster, int in_flight) {
    // note: never destroyed, as shared_render_context's contexts: renderers torn down by static
    // destructors at exit can outlive the driver (seen on NVIDIA's: a crash at exit).
    static auto* cache = new std::map<std::tuple<int, int, Raster, int>, Setup>();
    auto [it, inserted] = cache->try_emplace({kilo_triangles, supersample, raster, in_flight});
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
        const auto context =
            shared_render_context(ContextOptions{.backend = Backend::Vulkan, .raster = raster});
        const FrameOptions frame{.supersample = supersample};
        s.reference_renderer = std::make_unique<Renderer>(context, s.reference, frame);
        s.examined_renderer = std::make_unique<Renderer>(context, s.examined, frame);
        const GpuAtlasOptions options{.framed_radius = framing_sphere(s.reference).radius,
                                      .in_flight = in_flight};
        if (GpuAtlas::supported(*s.reference_renderer, *s.examined_renderer, options, &s.why))
            s.atlas =
                std::make_unique<GpuAtlas>(*s.reference_renderer, *s.examined_renderer, options);
    }
    return s;
}

void BM_GpuAtlasSweep(benchmark::State& state) {
    using Clock = std::chrono::steady_clock;
    const int kilo = static_cast<int>(state.range(0));
    const int size = static_cast<int>(state.range(1));
    const int supersample = static_cast<int>(state.range(2));
    const Raster raster = state.range(3) == 0 ? Raster::Graphics : Raster::Compute;
    const int in_flight = static_cast<int>(state.range(4));
    Setup& s = setup(kilo, supersample, raster, in_flight);
    if (!s.atlas) {
        state.SkipWithError(("the Vulkan device cannot run the GPU atlas: " + s.why).c_str());
        return;
    }
    // 60 views on a GPU (a sweep's default count); 8 on a CPU device (lavapipe takes 0.3-2 s a
    // view here), where the totals' share of a sweep is then larger: compare run_views_per_s.
    const int view_count = s.reference_renderer->info().device_type == "cpu" ? 8 : 60;
    const std::vector<View> views = bench::ring_views(s.reference, size, view_count);
    // One sweep untimed: first-use costs (targets, the pixel buffer, descriptor sets).
    s.atlas->run(views);
    benchmark::DoNotOptimize(s.atlas->read_totals());
    double run_s = 0.0;
    double totals_s = 0.0;
    std::size_t compared = 0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        s.atlas->run(views, [&](std::size_t, const ViewNumbers& n) { compared += n.compared; });
        const auto t1 = Clock::now();
        benchmark::DoNotOptimize(s.atlas->read_totals());
        const auto t2 = Clock::now();
        run_s += std::chrono::duration<double>(t1 - t0).count();
        totals_s += std::chrono::duration<double>(t2 - t1).count();
    }
    if (compared == 0) state.SkipWithError("no pixel was compared");
    const auto sweeps = static_cast<double>(state.iterations());
    const double views_run = view_count * sweeps;
    state.counters["views_per_s"] = views_run / (run_s + totals_s);
    state.counters["run_views_per_s"] = views_run / run_s;
    state.counters["totals_ms"] = 1e3 * totals_s / sweeps;
    const GpuAtlasTimings& t = s.atlas->timings();
    state.counters["totals_copy_ms"] = 1e3 * t.totals_copy_s;
    state.counters["totals_convert_ms"] = 1e3 * t.totals_convert_s;
    state.counters["host_wait_us"] = 1e6 * t.host_wait_s / view_count;
    state.counters["host_work_us"] = 1e6 * t.host_work_s / view_count;
    if (t.measured && t.views > 0) {
        const double per_view_ms = 1e3 / static_cast<double>(t.views);
        state.counters["dev_render_ms"] = t.render_s * per_view_ms;
        state.counters["dev_pixels_ms"] = t.pixels_s * per_view_ms;
        state.counters["dev_vertices_ms"] = t.vertices_s * per_view_ms;
        // The last sweep's device time over the mean sweep's wall time.
        state.counters["dev_busy"] = (t.render_s + t.pixels_s + t.vertices_s) / (run_s / sweeps);
    }
    state.SetLabel(std::to_string(s.reference.triangle_count()) + " tri " + std::to_string(size) +
                   "² s=" + std::to_string(supersample) + " " + to_string(raster) + " " +
                   std::to_string(in_flight) + " in flight | " +
                   s.reference_renderer->info().device_name);
}

BENCHMARK(BM_GpuAtlasSweep)
    ->ArgsProduct({{100, 1000}, {512, 1024}, {1}, {0, 1}, {2}})
    ->Args({1000, 1024, 2, 0, 2})
    ->Args({1000, 1024, 2, 1, 2})
    ->Args({1000, 1024, 1, 1, 4})
    ->ArgNames({"ktri", "size", "s", "raster", "flight"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);

}  // namespace
}  // namespace glint
