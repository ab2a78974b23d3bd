// The whole inspection in one process, stage by stage, as `glint sweep REF EXA --register`
// runs it with its defaults (60 views at 256², s = 2, per-view PNG pictures, mosaic,
// atlas.png, atlas files, report.json / report.html), on the benchmarks' blob pair
// (bench/blob_pair.h: ~200k and ~2M triangles) read from binary PLY files.
// Counters, seconds per run: load (both files), fit, distance, render, compare_atlas
// (compare + back-projection), decision, export; peak_rss_mib: this process's peak resident
// memory so far (it also holds the generated pair; bench/peers_bench.cpp measures the glint
// process alone).
#include "bench/blob_pair.h"
#include "mesh/io.h"
#include "mesh/write.h"
#include "report/inspect.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>

namespace glint {
namespace {

namespace fs = std::filesystem;

void BM_Sweep(benchmark::State& state) {
    const fs::path folder =
        fs::temp_directory_path() / ("glint_bench_sweep_" + std::to_string(getpid()));
    fs::create_directories(folder);
    {
        const bench::BlobPair pair = bench::make_blob_pair(static_cast<int>(state.range(0)));
        write_ply(pair.reference, folder / "reference.ply");
        write_ply(pair.examined, folder / "examined.ply");
    }
    InspectOptions options;
    options.analysis.fit.mode = FitMode::Register;
    options.exports.output = folder / "out";
    options.exports.replace_existing = true;  // the benchmark repeats into one folder
    std::size_t regions = 0, triangles = 0;
    double load_s = 0, fit_s = 0, distance_s = 0, render_s = 0, compare_s = 0, decision_s = 0,
           export_s = 0;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        const LoadedMesh reference = load_mesh(folder / "reference.ply");
        const LoadedMesh examined = load_mesh(folder / "examined.ply");
        load_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const Inspection inspection = inspect(reference.mesh, examined.mesh, options, {});
        const AnalysisResult& result = inspection.analysis;
        fit_s += result.fit_seconds;
        distance_s += result.distance_seconds;
        render_s += result.sweep.render_seconds;
        compare_s += result.sweep.compare_seconds;
        decision_s += result.decision_seconds;
        export_s += inspection.export_seconds;
        regions = result.decisions[0].regions.regions.size();
        triangles = reference.mesh.triangle_count();
    }
    fs::remove_all(folder);
    const auto per_run = [&](double total) {
        return total / static_cast<double>(state.iterations());
    };
    state.counters["load_s"] = per_run(load_s);
    state.counters["fit_s"] = per_run(fit_s);
    state.counters["distance_s"] = per_run(distance_s);
    state.counters["render_s"] = per_run(render_s);
    state.counters["compare_atlas_s"] = per_run(compare_s);
    state.counters["decision_s"] = per_run(decision_s);
    state.counters["export_s"] = per_run(export_s);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    state.counters["peak_rss_mib"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
    state.counters["regions"] = static_cast<double>(regions);
    state.counters["ref_triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_Sweep)->Arg(1)->Arg(2)->ArgName("size_class")->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace glint
