// Views per second of the sweep's per-view work on every path, side by side in one run
// (issue 13): run_sweep as the analysis calls it, with
//   embree     CPU ray casting, each band of rows of both frames compared and scattered by the
//              worker that traced it (the default on a machine without a GPU);
//   readback   Vulkan: both frames rendered, read back, compared and back-projected on the CPU
//              (accumulate = host);
//   gpu        Vulkan: compare and back-projection on the device (accumulate = gpu, the default
//              with a GPU); only per-vertex totals come back, once per sweep.
// On this machine Vulkan is lavapipe (the CPU); on a GPU machine the GPU is picked, or name it
// with GLINT_DEVICE=NVIDIA. Run: tools/bench scanner_views.
//
// The pair: bench/bumpy_sphere.h at 100k and 1M triangles as the reference, the same surface
// 5 % more finely tessellated with a dent as the examined mesh. A rotary plan of 16 views
// (azimuth every 45°, elevations ±30°) at 512² and 1024², s = 1, angle metric. views_per_s =
// views / (render + compare seconds of SweepResult): the per-view work, without creating the
// renderers (BVH or mesh upload, once per sweep: setup_s) and without the coverage step;
// total_s is the whole run_sweep. Each iteration is one sweep; tools/bench's repetitions give
// the medians.
#include "bench/bumpy_sphere.h"
#include "mesh/damage.h"
#include "scanner/plan.h"
#include "scanner/sweep.h"

#include <benchmark/benchmark.h>

#include <map>
#include <string>

namespace glint {
namespace {

enum class Path { Embree = 0, ReadBack = 1, Gpu = 2 };

struct Pair {
    Mesh reference;
    Mesh examined;
};

const Pair& pair(int kilo_triangles) {
    static std::map<int, Pair> cache;
    auto [it, inserted] = cache.try_emplace(kilo_triangles);
    if (inserted) {
        const int rings = kilo_triangles >= 1000 ? 500 : 158;
        it->second.reference = bench::bumpy_sphere(rings);
        it->second.examined = bench::bumpy_sphere(rings * 21 / 20);
        apply_damage(it->second.examined, {DamageSpec{.kind = DamageKind::Dent,
                                                      .center = {0.0, 1.0, 0.3},
                                                      .radius = 0.25,
                                                      .depth = 0.02}});
    }
    return it->second;
}

void BM_SweepViews(benchmark::State& state) {
    const auto path = static_cast<Path>(state.range(0));
    const Pair& p = pair(static_cast<int>(state.range(1)));
    SweepOptions options;
    options.plan.azimuth_step_deg = 45.0;
    options.plan.elevations_deg = {-30.0, 30.0};
    options.plan.size = static_cast<int>(state.range(2));
    options.render.supersample = 1;
    options.render.backend = path == Path::Embree ? Backend::Embree : Backend::Vulkan;
    options.accumulate = path == Path::Gpu ? Accumulation::Gpu : Accumulation::Host;
    const SweepPlan plan = make_sweep_plan(p.reference, options.plan);
    double per_view_s = 0.0, total_s = 0.0, setup_s = 0.0;
    std::string device;
    for (auto _ : state) {
        SweepResult r;
        try {
            r = run_sweep(p.reference, p.examined, plan, options);
        } catch (const std::exception& e) {
            state.SkipWithError(e.what());  // e.g. a device without the GPU atlas's features
            return;
        }
        const double views_s = r.render_seconds + r.compare_seconds;
        per_view_s += views_s;
        total_s += r.total_seconds;
        // Everything before the first view is renderer creation (the coverage step after the
        // last view is small and counted here too).
        setup_s += r.total_seconds - views_s;
        device = r.renderer.device_name;
        benchmark::DoNotOptimize(r.zooms);
    }
    const auto runs = static_cast<double>(state.iterations());
    state.counters["views_per_s"] = static_cast<double>(plan.views.size()) * runs / per_view_s;
    state.counters["total_s"] = total_s / runs;
    state.counters["setup_s"] = setup_s / runs;
    static const char* const names[] = {"embree", "readback", "gpu"};
    state.SetLabel(std::string(names[state.range(0)]) + " " +
                   std::to_string(p.reference.triangle_count()) + " tri " +
                   std::to_string(options.plan.size) + "² | " + device);
}

BENCHMARK(BM_SweepViews)
    ->ArgsProduct({{static_cast<int>(Path::Embree), static_cast<int>(Path::ReadBack),
                    static_cast<int>(Path::Gpu)},
                   {100, 1000},
                   {512, 1024}})
    ->ArgNames({"path", "ktri", "size"})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace glint
