#include "scanner/run_scenario.h"

#include "mesh/error.h"
#include "scanner/analysis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace glint {

namespace fs = std::filesystem;

namespace {

std::string fmt(const char* f, double a, double b) {
    char buf[160];
    std::snprintf(buf, sizeof buf, f, a, b);
    return buf;
}

// Files a scenario needs from the shared data folder; the first missing one, or "".
std::string missing_input(const Scenario& sc) {
    for (const auto* s : {&sc.reference, &sc.examined})
        if (!s->phantom && !s->mesh.empty() && !fs::exists(s->mesh))
            return s->mesh.string() + (s->needs_data_root ? " (shared data; give --data-root or GLINT_DATA)" : "");
    if (!sc.truth_mask.empty() && !fs::exists(sc.truth_mask)) return sc.truth_mask.string();
    return "";
}

}  // namespace

ScenarioOutcome run_scenario(const Scenario& sc, const ScenarioRunOptions& run) {
    const auto t0 = std::chrono::steady_clock::now();
    ScenarioOutcome out;
    out.name = sc.name;
    out.file = sc.file;
    if (const std::string missing = missing_input(sc); !missing.empty()) {
        // Scenarios tagged "data" use the shared data folder: its absence is a skip, not an
        // error. Any other missing input is an error.
        const bool shared = std::find(sc.tags.begin(), sc.tags.end(), "data") != sc.tags.end();
        if (!shared) throw IoError("scenario \"" + sc.file.string() + "\": input not found: " + missing);
        out.skipped = true;
        out.skip_reason = "input not found: " + missing;
        return out;
    }
    const ScenarioMeshes meshes = build_scenario_meshes(sc);
    out.reference_vertices = meshes.reference.vertex_count();

    AnalysisOptions options = sc.analysis;
    if (options.fit.mode == FitMode::Truth) options.fit.truth = meshes.true_reference_from_examined;
    if (!run.output_root.empty()) {
        ExportOptions& e = options.exports;
        e.output = run.output_root / sc.name;
        e.write_views = e.write_exr = run.write_views;
        e.command_line = run.command_line;
        auto describe_source = [](const SurfaceSource& s) {
            return s.phantom ? "phantom " + to_string(s.phantom->kind) + " " + to_string(s.phantom->scheme) + " " +
                                   std::to_string(s.phantom->resolution)
                             : std::string();
        };
        e.inputs.push_back({"scenario", sc.file, sc.name, 0, 0});
        e.inputs.push_back({"reference", sc.reference.phantom ? fs::path() : sc.reference.mesh,
                            describe_source(sc.reference), meshes.reference.vertex_count(),
                            meshes.reference.triangle_count()});
        e.inputs.push_back({"examined", sc.examined_derived ? fs::path() : sc.examined.mesh,
                            sc.examined_derived ? "derived from the reference" : describe_source(sc.examined),
                            meshes.examined.vertex_count(), meshes.examined.triangle_count()});
    }
    AnalysisObserver observer;
    observer.views = run.progress;
    const AnalysisResult result = analyse(meshes.reference, meshes.examined, options, observer);
    out.fit_mode = to_string(result.fit.mode);
    if (meshes.has_truth_pose) out.pose = pose_error(result.fit.reference_from_examined, meshes.true_reference_from_examined);
    out.views = result.sweep.plan.views.size();
    out.output = result.output;
    const ZoomDecision& z0 = result.decisions.front();
    out.regions = z0.regions.regions.size();
    out.largest_kind = z0.regions.regions.empty() ? "" : to_string(z0.regions.regions.front().kind);
    out.coverage = result.sweep.zooms.front().coverage.fraction;
    out.threshold_deg = z0.normal.value;
    if (!meshes.truth.empty())
        out.score = score_detection(meshes.reference, z0.regions.region_of_vertex, meshes.truth, z0.regions.regions);

    // [expect]
    const auto& e = sc.expect;
    auto fail = [&](const std::string& what) { out.failures.push_back(what); };
    if (e.regions && out.regions != *e.regions) fail(fmt("regions = %.0f, expected %.0f", double(out.regions), double(*e.regions)));
    if (e.min_regions && out.regions < *e.min_regions) fail(fmt("regions = %.0f, expected at least %.0f", double(out.regions), double(*e.min_regions)));
    if (e.max_regions && out.regions > *e.max_regions) fail(fmt("regions = %.0f, expected at most %.0f", double(out.regions), double(*e.max_regions)));
    if (e.kind && out.largest_kind != *e.kind) fail("largest region is '" + out.largest_kind + "', expected " + *e.kind);
    if (e.min_coverage && out.coverage < *e.min_coverage) fail(fmt("coverage = %.3f, expected at least %.3f", out.coverage, *e.min_coverage));
    auto need_score = [&](const char* key) {
        if (!out.score) fail(std::string(key) + " needs ground truth, the scenario has none");
        return out.score.has_value();
    };
    if (e.min_iou && need_score("min_iou") && out.score->iou < *e.min_iou) fail(fmt("IoU = %.3f, expected at least %.3f", out.score->iou, *e.min_iou));
    if (e.min_f1 && need_score("min_f1") && out.score->f1 < *e.min_f1) fail(fmt("F1 = %.3f, expected at least %.3f", out.score->f1, *e.min_f1));
    if (e.min_precision && need_score("min_precision") && out.score->precision < *e.min_precision)
        fail(fmt("precision = %.3f, expected at least %.3f", out.score->precision, *e.min_precision));
    if (e.min_recall && need_score("min_recall") && out.score->recall < *e.min_recall)
        fail(fmt("recall = %.3f, expected at least %.3f", out.score->recall, *e.min_recall));
    if (e.max_centroid_error && need_score("max_centroid_error")) {
        if (!out.score->centroid_error) fail("no region to measure the centroid error on");
        else if (*out.score->centroid_error > *e.max_centroid_error)
            fail(fmt("centroid error = %.4g, expected at most %.4g", *out.score->centroid_error, *e.max_centroid_error));
    }
    if (e.max_rotation_error_deg || e.max_translation_error) {
        if (!out.pose) fail("registration error expected but the scenario has no true pose");
        else {
            if (e.max_rotation_error_deg && out.pose->rotation_deg > *e.max_rotation_error_deg)
                fail(fmt("rotation error = %.5f°, expected at most %.5f°", out.pose->rotation_deg, *e.max_rotation_error_deg));
            if (e.max_translation_error && out.pose->translation > *e.max_translation_error)
                fail(fmt("translation error = %.5g, expected at most %.5g", out.pose->translation, *e.max_translation_error));
        }
    }
    if (e.min_region_shape_change) {
        for (const auto& r : z0.regions.regions) {
            if (std::abs(r.peak_depth) < *e.min_region_shape_change) {
                std::ostringstream m;
                m << std::fixed << std::setprecision(2) << "region " << r.id << " at (" << r.centroid.x() << ", " << r.centroid.y() << ", "
                  << r.centroid.z() << "): largest surface distance " << std::setprecision(3) << std::abs(r.peak_depth)
                  << ", expected at least " << *e.min_region_shape_change
                  << " (a region with no shape change behind it)";
                fail(m.str());
            }
        }
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace glint
