// The whole sweep as a user runs it: register + per-vertex distance + 72 views at 512² +
// atlas and exports, on the registration benchmark's pair (200k and 2M triangles).
// Counter peak_rss_mib: the process's peak resident memory so far (includes the meshes).
#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "scanner/fit.h"
#include "scanner/output_folder.h"
#include "scanner/report.h"
#include "scanner/sweep.h"

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

    SweepOptions options;
    options.plan.azimuth_step_deg = 30.0;
    options.plan.elevations_deg = {-75, -45, -15, 15, 45, 75};  // 12 × 6 = 72 views
    options.plan.size = 512;
    options.render.supersample = 1;
    std::size_t regions = 0;
    for (auto _ : state) {
        const FitOutcome fit = fit_examined(reference, examined, {.mode = FitRequest::Mode::Register});
        Mesh fitted = examined;
        transform_mesh(fitted, fit.reference_from_examined);
        const std::vector<float> distance = signed_distances(reference, fitted);
        const SweepPlan plan = make_sweep_plan(reference, options.plan);
        OutputFolder folder(std::filesystem::temp_directory_path() / "glint_bench_sweep");
        SweepExporter exporter(folder, plan, {.write_views = false, .write_exr = false});
        const SweepResult result = run_sweep(reference, fitted, plan, options, exporter.observer(), distance);
        exporter.finish();
        ReportContext context;
        context.distance = distance;
        context.fit_json = fit.json;
        write_sweep_outputs(folder, reference, result, context);
        folder.commit();
        regions = result.zooms[0].regions.regions.size();
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    state.counters["peak_rss_mib"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
    state.counters["regions"] = static_cast<double>(regions);
    state.counters["ref_triangles"] = static_cast<double>(reference.triangle_count());
}
BENCHMARK(BM_Sweep)->Arg(1)->Arg(2)->ArgName("size_class")->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace glint
