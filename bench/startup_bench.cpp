// How long glint takes before it does anything, as a user starts it: whole processes of
// `glint --version`, `glint --help` and `glint info` on a 1 280-triangle phantom PLY, wall time
// from spawn to exit (UseRealTime) and the peak resident memory (counter peak_mib, from
// wait4). Most of this is the dynamic loader mapping and relocating the libraries glint
// links; OpenImageIO, ITK, GDCM and VTK are plugins opened on first use (image/, volume/),
// so none of these runs maps them (tests/tools: cli.glint_links_no_*_libraries).
//
// For a before/after comparison build both and alternate them in one run (the machines are
// shared and noisy): GLINT_STARTUP_OTHER=<other glint> adds the same rows for that program.
#include "bench/process_run.h"
#include "mesh/phantom.h"
#include "mesh/write.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path& small_mesh() {
    static const fs::path path = [] {
        const fs::path dir = fs::temp_directory_path() / "glint_bench_startup";
        fs::create_directories(dir);
        const fs::path file = dir / "sphere_1280.ply";
        write_ply(make_phantom({.resolution = 3}), file);  // an icosphere of 1 280 triangles
        return file;
    }();
    return path;
}

void run(benchmark::State& state, const std::string& program, std::vector<std::string> args) {
    args.insert(args.begin(), program);
    double peak = 0.0;
    for (auto _ : state) {
        const bench::ProcessRun r = bench::run_process(args, {});
        state.SetIterationTime(r.seconds);
        peak = std::max(peak, r.peak_mib);
    }
    state.counters["peak_mib"] = peak;
}

void register_program(const std::string& label, const std::string& program) {
    benchmark::RegisterBenchmark((label + "/version").c_str(),
                                 [program](benchmark::State& s) { run(s, program, {"--version"}); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((label + "/help").c_str(),
                                 [program](benchmark::State& s) { run(s, program, {"--help"}); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((label + "/info_1280_triangles").c_str(),
                                 [program](benchmark::State& s) {
                                     run(s, program, {"info", small_mesh().string()});
                                 })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
}

// Registered at start-up (benchmark_main runs them): the other program only when given.
const bool registered = [] {
    register_program("glint", GLINT_EXECUTABLE);
    if (const char* other = std::getenv("GLINT_STARTUP_OTHER"); other != nullptr && *other != '\0')
        register_program("other", other);
    return true;
}();

}  // namespace
}  // namespace glint
