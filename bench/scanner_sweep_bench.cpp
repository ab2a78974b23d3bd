// The whole sweep as a user runs it: register + per-vertex distance + 72 views at 512² +
// atlas and exports, on the registration benchmark's pair (200k and 2M triangles).
// Counter peak_rss_mib: the process's peak resident memory so far (includes the meshes).
#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "scanner/analysis.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <filesystem>
#include <map>
#include <numbers>

namespace glint {
namespace {

Mesh blob(TessellationScheme scheme, int resolution) {
    Mesh m = make_phantom({.kind = PhantomKind::Ellipsoid, .scheme = scheme, .resolution = resolution, .radii = {12, 8, 6}});
    apply_damage(m, {DamageSpec{.kind = DamageKind::Bump, .center = {6.9, 4.0, 3.3}, .radius = 4, .depth = 1.5},
                     DamageSpec{.kind = DamageKind::Bump, .center = {-9.0, 0.0, -3.9}, .radius = 3, .depth = 1.0}});
    m.labels.clear();
    m.scalars.clear();
    return m;
}

void BM_Sweep(benchmark::State& state) {
    const bool big = state.range(0) == 2;
    const Mesh reference = blob(TessellationScheme::Uv, big ? 707 : 224);
    Mesh examined = blob(TessellationScheme::Ico, big ? 8 : 7);
    apply_damage(examined, {DamageSpec{.kind = DamageKind::Dent, .center = {0, -8, 0}, .radius = 1.2, .depth = 0.24}});
    Rigid truth = Rigid::Identity();
    truth.linear() = Eigen::AngleAxisd(5.0 * std::numbers::pi / 180, Vec3d(1, 2, 3).normalized()).toRotationMatrix();
    truth.translation() = Vec3d(0.48, 0, 0);
    transform_mesh(examined, truth.inverse());

    AnalysisOptions options;
    options.fit.mode = FitMode::Register;
    options.sweep.plan.azimuth_step_deg = 30.0;
    options.sweep.plan.elevations_deg = {-75, -45, -15, 15, 45, 75};  // 12 × 6 = 72 views
    options.sweep.plan.size = 512;
    options.sweep.render.supersample = 1;
    options.exports.output = std::filesystem::temp_directory_path() / "glint_bench_sweep";
    options.exports.replace_existing = true;  // the benchmark repeats into one folder
    options.exports.write_views = options.exports.write_exr = false;
    std::size_t regions = 0;
    double fit_s = 0, distance_s = 0, render_s = 0, compare_s = 0, decision_s = 0, export_s = 0;
    for (auto _ : state) {
        const AnalysisResult result = analyse(reference, examined, options);
        fit_s += result.fit_seconds;
        distance_s += result.distance_seconds;
        render_s += result.sweep.render_seconds;
        compare_s += result.sweep.compare_seconds;
        decision_s += result.decision_seconds;
        export_s += result.export_seconds;
        regions = result.decisions[0].regions.regions.size();
    }
    const auto per_run = [&](double total) { return total / static_cast<double>(state.iterations()); };
    // Where the time goes (seconds per run): the anchor (Open3D) covers fit + distance.
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
    state.counters["ref_triangles"] = static_cast<double>(reference.triangle_count());
}
BENCHMARK(BM_Sweep)->Arg(1)->Arg(2)->ArgName("size_class")->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace glint
