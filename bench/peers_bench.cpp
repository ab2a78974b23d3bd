// glint's whole inspection against its peer, as a user compares them: wall clocks of whole
// processes on the same pair of files (bench/blob_pair.h, written as binary PLY), alternating.
//
//   glint    `glint sweep REF EXA --register -o OUT --force` with every other option at its
//            default: load both files, fit, signed distance, 60 views at 256² (s = 2),
//            decision, atlas files, per-view PNG pictures, mosaic, atlas.png,
//            report.json / report.html;
//   Open3D   `/usr/bin/python3 bench/open3d_peer.py REF EXA`: import, load, point-to-plane ICP
//            coarse to fine and converged (gates 5 % then 1 % of the size, relative changes
//            1e-9, at most 100 iterations each: glint's accuracy is what such a user wants),
//            signed closest-point distance of every reference vertex (Debian's
//            python3-open3d); and the same with `--one-scale` (Open3D's defaults, once).
//
// note: whole processes, not analyse() in one process: a user compares the time from typing
// the command to having the results, which includes loading the files and writing every
// export; Open3D's import (~0.4 s) is part of its process as loading is part of glint's, and
// the counters give Open3D's time after the import too (open3d_work_s, ratio_work).
//
// One benchmark iteration is one round: both processes once, the first one alternating
// between rounds; run with --benchmark_repetitions (tools/bench: 5) the medians are the
// `_median` rows. Counters (seconds unless named otherwise): glint_s and open3d_s (process
// wall clocks, Open3D coarse to fine), ratio = glint_s / open3d_s, ratio_work = glint_s /
// open3d_work_s, open3d_one_scale_s and ratio_one_scale (Open3D's one-scale defaults),
// glint_peak_mib (glint's peak resident memory, from wait4), the rotation errors of both fits
// against the known motion (glint_rot_err_deg, open3d_rot_err_deg), and glint's stages from
// report.json's timings (glint_fit_s, _distance_s, _render_s, _compare_atlas_s, _decision_s;
// glint_rest_s = load + exports + process start).
// Without python3-open3d the Open3D half is skipped and the label says why.
// GLINT_BENCH_BASELINE=/path/to/an/older/glint adds that binary to every round (counters
// prefixed base_): before/after measured side by side on the same files;
// GLINT_BENCH_BASELINE_ARGS adds options to the baseline's command line only (e.g. "--no-exr"
// for a glint from before per-view EXRs became opt-in, so both write the same files).
// GLINT_BENCH_GLINT runs another glint executable than the build's (a copy carried to another
// machine); GLINT_BENCH_GLINT_ARGS adds options to its command line. With the baseline set to
// the same executable, the two differ only by their options: e.g. on a GPU machine
// GLINT_BENCH_GLINT_ARGS=--no-pictures and GLINT_BENCH_BASELINE_ARGS="--no-pictures --backend
// embree" measure the GPU's whole inspection against the CPU's in the same rounds.
#include "bench/blob_pair.h"
#include "bench/process_run.h"
#include "mesh/write.h"

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace glint {
namespace {

namespace fs = std::filesystem;
using bench::ProcessRun;
using bench::run_process;

struct Files {
    fs::path folder;
    fs::path reference;
    fs::path examined;
    Rigid truth;
    std::size_t triangles = 0;
};

// The pairs written, removed when the program ends (kept with GLINT_BENCH_KEEP_FILES=1, to
// profile a run on the same files).
struct FileCache {
    std::map<int, Files> pairs;
    ~FileCache() {
        if (std::getenv("GLINT_BENCH_KEEP_FILES") != nullptr) return;
        std::error_code ignored;
        for (const auto& [size_class, f] : pairs) fs::remove_all(f.folder, ignored);
    }
};

// The pair of a size class, written once per process into a folder of its own.
const Files& files(int size_class) {
    static FileCache files_written;
    auto& cache = files_written.pairs;
    if (auto it = cache.find(size_class); it != cache.end()) return it->second;
    std::string name = (fs::temp_directory_path() / "glint_bench_peers_XXXXXX").string();
    if (mkdtemp(name.data()) == nullptr)
        throw std::runtime_error("cannot create a folder under /tmp");
    bench::BlobPair pair = bench::make_blob_pair(size_class);
    Files f{name, fs::path(name) / "reference.ply", fs::path(name) / "examined.ply", pair.truth,
            pair.reference.triangle_count()};
    write_ply(pair.reference, f.reference);
    write_ply(pair.examined, f.examined);
    return cache.emplace(size_class, std::move(f)).first->second;
}

nlohmann::json read_json(const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

// Rotation error (degrees) of a fit given as a 4×4 list of rows against the true motion.
double rotation_error_deg(const nlohmann::json& rows, const Rigid& truth) {
    Rigid fit = Rigid::Identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            fit.matrix()(r, c) =
                rows.at(static_cast<std::size_t>(r)).at(static_cast<std::size_t>(c)).get<double>();
    return rotation_angle_deg(truth.inverse() * fit);
}

// Why Open3D cannot run here ("" when it can).
const std::string& open3d_missing() {
    static const std::string reason = [] {
        if (!fs::exists("/usr/bin/python3"))
            return std::string("Open3D skipped: /usr/bin/python3 not found");
        const int rc = std::system("/usr/bin/python3 -c 'import open3d' >/dev/null 2>&1");
        return rc == 0
                   ? std::string()
                   : std::string("Open3D skipped: python3-open3d is not installed (tools/setup)");
    }();
    return reason;
}

struct GlintRun {
    ProcessRun process;
    nlohmann::json report;
};

struct Round {
    GlintRun glint;
    std::optional<GlintRun> baseline;
    ProcessRun open3d;
    nlohmann::json peer;
    ProcessRun open3d_one_scale;
    nlohmann::json peer_one_scale;
};

GlintRun run_glint(const std::string& executable, const Files& f,
                   const char* extra_args = nullptr) {
    const fs::path out = f.folder / "glint_out";
    std::vector<std::string> argv{executable,   "sweep", f.reference.string(), f.examined.string(),
                                  "--register", "-o",    out.string(),         "--force"};
    if (extra_args != nullptr) {
        std::istringstream words(extra_args);
        for (std::string w; words >> w;) argv.push_back(w);
    }
    GlintRun r;
    r.process = run_process(argv, {});
    r.report = read_json(out / "report.json");
    return r;
}

// Open3D's script in one configuration ("" or "--one-scale"); its JSON into `peer`.
ProcessRun run_open3d(const Files& f, const std::string& option, nlohmann::json& peer) {
    const fs::path peer_json = f.folder / "open3d.json";
    std::vector<std::string> argv{"/usr/bin/python3", GLINT_OPEN3D_SCRIPT, f.reference.string(),
                                  f.examined.string()};
    if (!option.empty()) argv.push_back(option);
    const ProcessRun run = run_process(argv, peer_json);
    peer = read_json(peer_json);
    return run;
}

// One round; `first` rotates which process starts it (glint, Open3D twice, baseline).
Round run_round(const Files& f, int first) {
    Round r;
    const char* baseline = std::getenv("GLINT_BENCH_BASELINE");
    const bool open3d = open3d_missing().empty();
    const std::function<void()> steps[4] = {
        [&] {
            const char* other = std::getenv("GLINT_BENCH_GLINT");
            r.glint = run_glint(other != nullptr ? other : GLINT_EXECUTABLE, f,
                                std::getenv("GLINT_BENCH_GLINT_ARGS"));
        },
        [&] {
            if (open3d) r.open3d = run_open3d(f, "", r.peer);
        },
        [&] {
            if (open3d) r.open3d_one_scale = run_open3d(f, "--one-scale", r.peer_one_scale);
        },
        [&] {
            if (baseline != nullptr)
                r.baseline = run_glint(baseline, f, std::getenv("GLINT_BENCH_BASELINE_ARGS"));
        }};
    for (int k = 0; k < 4; ++k) steps[(first + k) % 4]();
    return r;
}

// glint's stages (report.json timings_s) and its fit's error, counters named prefix + stage.
void stage_counters(benchmark::State& state, const std::string& prefix, const GlintRun& g,
                    const Rigid& truth) {
    auto& c = state.counters;
    const auto& t = g.report.at("timings_s");
    c[prefix + "s"] = g.process.seconds;
    c[prefix + "peak_mib"] = g.process.peak_mib;
    c[prefix + "fit_s"] = t.at("fit").get<double>();
    c[prefix + "distance_s"] = t.at("distance").get<double>();
    c[prefix + "render_s"] = t.at("render").get<double>();
    c[prefix + "compare_atlas_s"] = t.at("compare_and_atlas").get<double>();
    c[prefix + "decision_s"] = t.at("decision").get<double>();
    c[prefix + "rest_s"] = g.process.seconds - t.at("total").get<double>();
    c[prefix + "rot_err_deg"] =
        rotation_error_deg(g.report.at("fit").at("reference_from_examined"), truth);
}

void BM_Peers(benchmark::State& state) {
    const Files& f = files(static_cast<int>(state.range(0)));
    static int rounds = 0;
    for (auto _ : state) {
        const Round r = run_round(f, rounds++ % 4);
        state.SetIterationTime(r.glint.process.seconds);
        stage_counters(state, "glint_", r.glint, f.truth);
        if (r.baseline) stage_counters(state, "base_", *r.baseline, f.truth);
        auto& c = state.counters;
        if (!r.peer.is_null()) {
            c["open3d_s"] = r.open3d.seconds;
            c["open3d_work_s"] = r.peer.at("work_s").get<double>();
            c["open3d_rot_err_deg"] =
                rotation_error_deg(r.peer.at("reference_from_examined"), f.truth);
            c["ratio"] = r.glint.process.seconds / r.open3d.seconds;
            c["ratio_work"] = r.glint.process.seconds / r.peer.at("work_s").get<double>();
            c["open3d_one_scale_s"] = r.open3d_one_scale.seconds;
            c["open3d_one_scale_rot_err_deg"] =
                rotation_error_deg(r.peer_one_scale.at("reference_from_examined"), f.truth);
            c["ratio_one_scale"] = r.glint.process.seconds / r.open3d_one_scale.seconds;
        }
    }
    state.counters["ref_triangles"] = static_cast<double>(f.triangles);
    if (!open3d_missing().empty()) state.SetLabel(open3d_missing());
}
BENCHMARK(BM_Peers)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("size_class")
    ->UseManualTime()
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
}  // namespace glint
