// Reference and examined frames in flight together (render_view_pairs) against the
// sequential path the sweep used before (the examined frame rendered inside the reference
// frame's callback), on Embree and on Vulkan (lavapipe here, the GPU where there is one).
// Run: tools/bench render_pairs
//
// The pair: the condyle phantom as an icosphere (level 6, 82k triangles) and as a UV mesh
// (160 rings, 102k triangles), the sweep's situation of two tessellations of one surface,
// both on one shared context. A ring of 16 views at 256² (s = 2, the sweep's default).
// BM_PairsVsSequential times both paths alternately inside each iteration, so they share
// the machine's state; its counters are per run of 16 views: sequential_ms, pairs_ms and
// speedup = sequential / pairs (the medians of tools/bench's repetitions are the figures).
#include "mesh/phantom.h"
#include "render/context.h"
#include "render/renderer.h"
#include "render/view.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <memory>
#include <utility>

namespace glint {
namespace {

struct Pair {
    Mesh reference;
    Mesh examined;
    std::unique_ptr<Renderer> reference_renderer;
    std::unique_ptr<Renderer> examined_renderer;
};

/// One pair of renderers per backend on the process's shared context; creation not timed.
Pair& bench_pair(Backend backend) {
    static std::map<int, Pair> cache;
    auto [it, inserted] = cache.try_emplace(static_cast<int>(backend));
    Pair& p = it->second;
    if (inserted) {
        p.reference = make_phantom(PhantomOptions{
            .kind = PhantomKind::Condyle, .scheme = TessellationScheme::Ico, .resolution = 6});
        p.examined = make_phantom(PhantomOptions{
            .kind = PhantomKind::Condyle, .scheme = TessellationScheme::Uv, .resolution = 160});
        const auto context = shared_render_context(ContextOptions{.backend = backend});
        const FrameOptions frame{.supersample = 2};
        p.reference_renderer = std::make_unique<Renderer>(context, p.reference, frame);
        p.examined_renderer = std::make_unique<Renderer>(context, p.examined, frame);
    }
    return p;
}

/// A sweep-like ring: `count` azimuths, the elevation alternating between +30° and −30°.
std::vector<View> ring_views(const Mesh& mesh, int size, int count) {
    std::vector<View> views(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
        const ViewSpec spec{.azimuth_deg = 360.0 * i / count,
                            .elevation_deg = i % 2 == 0 ? 30.0 : -30.0,
                            .width = size,
                            .height = size,
                            .index = i};
        views[static_cast<std::size_t>(i)] = make_view(mesh, spec);
    }
    return views;
}

/// The consumer's share of the work: reads every pixel of both frames.
std::size_t consume(const Frame& a, const Frame& b) {
    return a.covered_count() + b.covered_count();
}

std::size_t run_sequential(Pair& p, const std::vector<View>& views) {
    std::size_t covered = 0;
    p.reference_renderer->render_views(views, [&](std::size_t i, const Frame& reference) {
        const Frame examined = p.examined_renderer->render(views[i]);
        covered += consume(reference, examined);
    });
    return covered;
}

std::size_t run_pairs(Pair& p, const std::vector<View>& views) {
    std::size_t covered = 0;
    render_view_pairs(*p.reference_renderer, *p.examined_renderer, views,
                      [&](std::size_t, const Frame& reference, const Frame& examined) {
                          covered += consume(reference, examined);
                      });
    return covered;
}

void BM_PairsVsSequential(benchmark::State& state) {
    using Clock = std::chrono::steady_clock;
    const auto backend = static_cast<Backend>(state.range(0));
    Pair& p = bench_pair(backend);
    const std::vector<View> views = ring_views(p.reference, static_cast<int>(state.range(1)), 16);
    double sequential_s = 0.0;
    double pairs_s = 0.0;
    std::size_t covered_sequential = 0;
    std::size_t covered_pairs = 0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        covered_sequential += run_sequential(p, views);
        const auto t1 = Clock::now();
        covered_pairs += run_pairs(p, views);
        const auto t2 = Clock::now();
        sequential_s += std::chrono::duration<double>(t1 - t0).count();
        pairs_s += std::chrono::duration<double>(t2 - t1).count();
    }
    if (covered_sequential != covered_pairs)
        state.SkipWithError("pairs and sequential frames differ");
    const auto n = static_cast<double>(state.iterations());
    state.counters["sequential_ms"] = 1e3 * sequential_s / n;
    state.counters["pairs_ms"] = 1e3 * pairs_s / n;
    state.counters["speedup"] = pairs_s > 0.0 ? sequential_s / pairs_s : 0.0;
    state.SetLabel(to_string(backend) + " " + std::to_string(state.range(1)) + "² s=2 | " +
                   p.reference_renderer->info().device_name);
}

BENCHMARK(BM_PairsVsSequential)
    ->ArgsProduct({{static_cast<int>(Backend::Embree), static_cast<int>(Backend::Vulkan)}, {256}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

}  // namespace
}  // namespace glint
