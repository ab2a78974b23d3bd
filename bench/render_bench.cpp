// Render throughput: views per second, render + read-back + resolve, both backends side by
// side on the same meshes and views (issue #3). Run:
//   glint_bench_render --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// and read the *_median rows (items_per_second = views/s).
//
// Meshes: a bumpy latitude/longitude sphere with 100k and 1M triangles (exact analytic
// shape, no file needed). Views: 16 azimuth/elevation pairs around the mesh, orthographic,
// framed to fit, s = 1, rendered through Renderer::render_views (the streaming path the
// sweep uses) with a consumer that reads every pixel's coverage, so read-back is real.
// Also: resident memory while streaming a 360-view sweep at 512² (bounded, not ∝ views).
#include "bench/bumpy_sphere.h"
#include "mesh/mesh.h"
#include "mesh/normals.h"
#include "render/renderer.h"
#include "render/view.h"

#include <benchmark/benchmark.h>

#include <unistd.h>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <string>

namespace glint {
namespace {

const Mesh& bench_mesh(int kilo_triangles) {
    static std::map<int, Mesh> cache;
    auto it = cache.find(kilo_triangles);
    if (it == cache.end()) {
        // 4·r² ≈ triangles: r = 158 → 99.5k, r = 500 → 998k.
        const int rings = kilo_triangles >= 1000 ? 500 : 158;
        it = cache.emplace(kilo_triangles, bench::bumpy_sphere(rings)).first;
    }
    return it->second;
}

/// One renderer per (backend, mesh): creation (upload, BVH build) is not timed.
Renderer& bench_renderer(Backend backend, int kilo_triangles) {
    static std::map<std::pair<int, int>, std::unique_ptr<Renderer>> cache;
    auto& slot = cache[{static_cast<int>(backend), kilo_triangles}];
    if (!slot)
        slot = std::make_unique<Renderer>(bench_mesh(kilo_triangles),
                                          RenderOptions{.backend = backend});
    return *slot;
}

void BM_RenderViews(benchmark::State& state) {
    const auto backend = static_cast<Backend>(state.range(0));
    const int kilo = static_cast<int>(state.range(1));
    const int size = static_cast<int>(state.range(2));
    Renderer& renderer = bench_renderer(backend, kilo);
    const std::vector<View> views = bench::ring_views(bench_mesh(kilo), size, 16);
    std::size_t covered = 0;
    for (auto _ : state) {
        renderer.render_views(views,
                              [&](std::size_t, const Frame& f) { covered += f.covered_count(); });
    }
    benchmark::DoNotOptimize(covered);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(views.size()));
    state.SetLabel(to_string(backend) + " " + std::to_string(renderer.info().triangle_count) +
                   " tri " + std::to_string(size) + "² | " + renderer.info().device_name);
}

long resident_kib() {
    std::ifstream statm("/proc/self/statm");
    long pages_total = 0, pages_resident = 0;
    statm >> pages_total >> pages_resident;
    return pages_resident * (sysconf(_SC_PAGESIZE) / 1024);
}

// Memory of a 360-view sweep: resident size before the renderer exists, after it is built
// (mesh uploaded, BVH built), after the first frame (targets allocated) and the peak while
// streaming all 360 views. Bounded streaming shows as peak ≈ after-first-frame. Run this
// one alone (--benchmark_filter=sweep360) so earlier benchmarks' renderers do not count.
void BM_Sweep360Memory(benchmark::State& state) {
    const auto backend = static_cast<Backend>(state.range(0));
    const Mesh& mesh = bench_mesh(100);
    const std::vector<View> views = bench::ring_views(mesh, 512, 360);
    long before = 0, built = 0, first = 0, at_90 = 0, at_180 = 0, peak = 0;
    std::string device;
    for (auto _ : state) {
        before = resident_kib();
        Renderer renderer(mesh, RenderOptions{.backend = backend});
        device = renderer.info().device_name;
        built = resident_kib();
        peak = built;
        renderer.render_views(views, [&](std::size_t i, const Frame&) {
            const long now = resident_kib();
            if (i == 0) first = now;
            if (i == 90) at_90 = now;
            if (i == 180) at_180 = now;
            peak = std::max(peak, now);
        });
    }
    state.SetItemsProcessed(state.iterations() * 360);
    state.counters["renderer_MiB"] = static_cast<double>(built - before) / 1024.0;
    state.counters["first_frame_MiB"] = static_cast<double>(first - before) / 1024.0;
    state.counters["view90_MiB"] = static_cast<double>(at_90 - before) / 1024.0;
    state.counters["view180_MiB"] = static_cast<double>(at_180 - before) / 1024.0;
    state.counters["peak_MiB"] = static_cast<double>(peak - before) / 1024.0;
    state.SetLabel(to_string(backend) + " 360 views 512² 100k tri | " + device);
}

void register_all() {
    for (const Backend b : {Backend::Vulkan, Backend::Embree}) {
        for (const int kilo : {100, 1000}) {
            for (const int size : {512, 1024}) {
                benchmark::RegisterBenchmark(("render/" + to_string(b)).c_str(), BM_RenderViews)
                    ->Args({static_cast<long>(b), kilo, size})
                    ->ArgNames({"backend", "ktri", "size"})
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime()
                    ->MinTime(1.0);
            }
        }
    }
    for (const Backend b : {Backend::Vulkan, Backend::Embree}) {
        benchmark::RegisterBenchmark(("sweep360/" + to_string(b)).c_str(), BM_Sweep360Memory)
            ->Args({static_cast<long>(b)})
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(1);
    }
}

// Registered at start-up (benchmark_main runs them): the argument grid is built in code.
const bool kRegistered = (register_all(), true);

}  // namespace
}  // namespace glint
