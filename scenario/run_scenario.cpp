#include "scenario/run_scenario.h"

#include "analysis/analysis.h"
#include "mesh/error.h"
#include "mesh/input_path.h"
#include "report/inspect.h"
#include "report/run_inputs.h"
#include "scenario/detail/asymmetry_run.h"

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

// Scores against the truth, the tallies of regions, and the plain-distance baseline.
void score_outcome(const Scenario& sc, const ScenarioMeshes& meshes, const AnalysisResult& result,
                   ScenarioOutcome& out) {
    const ZoomDecision& z0 = result.decisions.front();
    if (meshes.truth.empty() && meshes.true_distance.empty()) return;
    PairTruth truth{meshes.truth, meshes.truth_damage};
    if (truth.damage_id.empty() && !truth.damaged.empty())
        for (const auto d : truth.damaged) truth.damage_id.push_back(d ? 1 : 0);
    const PairTruth* t = truth.damaged.empty() ? nullptr : &truth;
    const double close = sc.expect.region_min_true_distance;
    out.tally = tally_regions(z0.regions.region_of_vertex, t, meshes.true_distance, close);
    if (t)
        out.score = score_detection(meshes.reference, z0.regions.region_of_vertex, meshes.truth,
                                    z0.regions.regions);
    double threshold = sc.baseline_distance.value_or(0.0);
    if (!sc.baseline_distance && !sc.damages.empty()) {
        double depth = sc.damages.front().depth;
        for (const auto& d : sc.damages) depth = std::min(depth, d.depth);
        threshold = kDamageLabelThreshold * depth;
    }
    if (threshold <= 0 || result.distance.size() != meshes.reference.vertex_count()) return;
    const BaselineResult b = distance_baseline(meshes.reference, result.distance, threshold);
    ScenarioOutcome::Baseline base;
    base.threshold = threshold;
    base.tally = tally_regions(b.region_of_vertex, t, meshes.true_distance, close);
    if (t) base.score = score_detection(meshes.reference, b.region_of_vertex, meshes.truth, {});
    out.baseline = base;
}

// The [expect] entries that do not hold, into out.failures.
void check_expect(const ScenarioExpect& e, const std::vector<Region>& regions,
                  ScenarioOutcome& out) {
    auto fail = [&](const std::string& what) { out.failures.push_back(what); };
    if (e.regions && out.regions != *e.regions)
        fail(fmt("regions = %.0f, expected %.0f", double(out.regions), double(*e.regions)));
    if (e.min_regions && out.regions < *e.min_regions)
        fail(fmt("regions = %.0f, expected at least %.0f", double(out.regions),
                 double(*e.min_regions)));
    if (e.max_regions && out.regions > *e.max_regions)
        fail(fmt("regions = %.0f, expected at most %.0f", double(out.regions),
                 double(*e.max_regions)));
    if (e.kind && out.largest_kind != *e.kind)
        fail("largest region is '" + out.largest_kind + "', expected " + *e.kind);
    if (e.first_kind && out.first_kind != *e.first_kind)
        fail("first region is '" + out.first_kind + "', expected " + *e.first_kind);
    if (e.min_first_area && !(out.first_area >= *e.min_first_area))
        fail(fmt("first region's area = %.4g, expected at least %.4g", out.first_area,
                 *e.min_first_area));
    if (e.max_first_area && !(out.first_area <= *e.max_first_area))
        fail(fmt("first region's area = %.4g, expected at most %.4g", out.first_area,
                 *e.max_first_area));
    if (e.min_first_volume_lost && !(-out.first_volume >= *e.min_first_volume_lost))
        fail(fmt("first region's volume lost = %.4g, expected at least %.4g", -out.first_volume,
                 *e.min_first_volume_lost));
    if (e.max_p_value)
        for (const auto& r : regions)
            if (std::isfinite(r.p_value) && !(r.p_value <= *e.max_p_value))
                fail("region " + std::to_string(r.id) + "'s family-wise p = " +
                     fmt("%.3g, expected at most %.3g", r.p_value, *e.max_p_value));
    if (e.every_kind)
        for (const auto& r : regions)
            if (to_string(r.kind) != *e.every_kind)
                fail("region " + std::to_string(r.id) + " is '" + to_string(r.kind) +
                     "', expected " + *e.every_kind);
    if (e.min_compared && out.compared < *e.min_compared)
        fail(fmt("compared = %.3f, expected at least %.3f", out.compared, *e.min_compared));
    if (e.max_compared && out.compared > *e.max_compared)
        fail(fmt("compared = %.3f, expected at most %.3f", out.compared, *e.max_compared));
    if (e.min_coverage && out.coverage < *e.min_coverage)
        fail(fmt("coverage = %.3f, expected at least %.3f", out.coverage, *e.min_coverage));
    auto need_score = [&](const char* key) {
        if (!out.score) fail(std::string(key) + " needs ground truth, the scenario has none");
        return out.score.has_value();
    };
    if (e.min_iou && need_score("min_iou") && out.score->iou < *e.min_iou)
        fail(fmt("IoU = %.3f, expected at least %.3f", out.score->iou, *e.min_iou));
    if (e.min_f1 && need_score("min_f1") && out.score->f1 < *e.min_f1)
        fail(fmt("F1 = %.3f, expected at least %.3f", out.score->f1, *e.min_f1));
    if (e.min_precision && need_score("min_precision") && out.score->precision < *e.min_precision)
        fail(fmt("precision = %.3f, expected at least %.3f", out.score->precision,
                 *e.min_precision));
    if (e.min_recall && need_score("min_recall") && out.score->recall < *e.min_recall)
        fail(fmt("recall = %.3f, expected at least %.3f", out.score->recall, *e.min_recall));
    if (e.max_centroid_error && need_score("max_centroid_error")) {
        if (!out.score->centroid_error) fail("no region to measure the centroid error on");
        else if (*out.score->centroid_error > *e.max_centroid_error)
            fail(fmt("centroid error = %.4g, expected at most %.4g", *out.score->centroid_error,
                     *e.max_centroid_error));
    }
    if (e.warning && std::none_of(out.warnings.begin(), out.warnings.end(), [&](const auto& w) {
            return w.find(*e.warning) != std::string::npos;
        }))
        fail("no warning contains \"" + *e.warning + "\"");
    if (e.max_scale_error) {
        if (!out.pose) fail("scale error expected but the scenario has no true pose");
        else if (out.pose->scale > *e.max_scale_error)
            fail(fmt("scale error = %.5f, expected at most %.5f", out.pose->scale,
                     *e.max_scale_error));
    }
    if (e.max_rotation_error_deg || e.max_translation_error) {
        if (!out.pose) fail("registration error expected but the scenario has no true pose");
        else {
            if (e.max_rotation_error_deg && out.pose->rotation_deg > *e.max_rotation_error_deg)
                fail(fmt("rotation error = %.5f°, expected at most %.5f°", out.pose->rotation_deg,
                         *e.max_rotation_error_deg));
            if (e.max_translation_error && out.pose->translation > *e.max_translation_error)
                fail(fmt("translation error = %.5g, expected at most %.5g", out.pose->translation,
                         *e.max_translation_error));
        }
    }
    if (e.min_region_shape_change) {
        for (const auto& r : regions) {
            if (std::abs(r.peak_depth) < *e.min_region_shape_change) {
                std::ostringstream m;
                m << std::fixed << std::setprecision(2) << "region " << r.id << " at ("
                  << r.centroid.x() << ", " << r.centroid.y() << ", " << r.centroid.z()
                  << "): largest surface distance " << std::setprecision(3)
                  << std::abs(r.peak_depth) << ", expected at least " << *e.min_region_shape_change
                  << " (a region with no shape change behind it)";
                fail(m.str());
            }
        }
    }
    if (e.max_false_regions || e.all_damages_detected || e.max_close_region_vertices) {
        if (!out.tally) {
            fail(
                "false regions / damages detected need ground truth or true distances, the scenario has none");
        } else {
            const RegionTally& t = *out.tally;
            if (e.max_false_regions && t.false_regions > *e.max_false_regions)
                fail(fmt("false regions = %.0f, expected at most %.0f", double(t.false_regions),
                         double(*e.max_false_regions)));
            if (e.all_damages_detected && t.damages_detected < t.damages)
                fail(fmt("damages detected = %.0f of %.0f, expected all",
                         double(t.damages_detected), double(t.damages)));
            if (e.max_close_region_vertices &&
                t.close_region_vertices > *e.max_close_region_vertices)
                fail(fmt("region vertices closer than %.3g to the examined surface = %.0f",
                         e.region_min_true_distance, double(t.close_region_vertices)) +
                     ", expected at most " + std::to_string(*e.max_close_region_vertices));
        }
    }
}

// The ground truth beside glint's own fields in the atlas files, so a viewer shows both:
// "truth_damage_id" (the 1-based damage a vertex belongs to, 0 = undamaged) and
// "truth_distance_<unit>" (unsigned distance to the examined surface placed back with the
// true pose, before noise; report/export_options.h expands "{unit}").
void add_truth_scalars(const ScenarioMeshes& meshes, ExportOptions& e) {
    const std::size_t n = meshes.reference.vertex_count();
    if (meshes.truth.size() == n) {
        std::vector<float> id(n);
        for (std::size_t v = 0; v < n; ++v)
            id[v] = !meshes.truth[v]                  ? 0.0f
                    : meshes.truth_damage.size() == n ? static_cast<float>(meshes.truth_damage[v])
                                                      : 1.0f;
        e.extra_scalars.emplace_back("truth_damage_id", std::move(id));
    }
    if (meshes.true_distance.size() == n)
        e.extra_scalars.emplace_back("truth_distance{unit}", meshes.true_distance);
}

}  // namespace

namespace detail {

std::string describe_source(const SurfaceSource& s) {
    return s.phantom
               ? "phantom " + to_string(s.phantom->kind) + " " + to_string(s.phantom->scheme) +
                     " " + std::to_string(s.phantom->resolution)
               : std::string();
}

InspectOptions scenario_inspect_options(const Scenario& sc, const ScenarioRunOptions& run,
                                        const ScenarioMeshes& meshes, RunRecord& record) {
    InspectOptions options{.analysis = sc.analysis};
    AnalysisOptions& analysis = options.analysis;
    if (analysis.fit.mode == FitMode::Truth) {
        analysis.fit.truth = meshes.true_reference_from_examined;
        analysis.fit.truth_scale = meshes.true_examined_scale;
    }
    if (!run.unit.empty()) analysis.units.unit = run.unit;
    analysis.units.allow_scale_mismatch =
        analysis.units.allow_scale_mismatch || run.allow_scale_mismatch;
    record.command_line = run.command_line;
    if (run.output_root.empty()) return options;
    ExportOptions& e = options.exports;
    e = scenario_exports(sc, run.write_views, run.write_pictures);
    e.output = run.output_root / sc.name;
    e.replace_existing = run.replace_existing;
    record.add_file("scenario", sc.file, sc.name);
    record.inputs.push_back({"reference", sc.reference.phantom ? fs::path() : sc.reference.mesh,
                             describe_source(sc.reference), meshes.reference.vertex_count(),
                             meshes.reference.triangle_count(), to_string(reference_space(sc))});
    return options;
}

}  // namespace detail

ExportOptions scenario_exports(const Scenario& sc, bool views, bool pictures) {
    ExportOptions e = sc.exports;
    e.write_views = e.write_views || views;
    e.write_pictures = e.write_pictures && pictures;
    return e;
}

std::string missing_input(const Scenario& sc) {
    const auto missing = [&](const fs::path& p) {
        return !reachable_input(
            p, "scenario \"" + sc.file.string() + "\": input \"" + p.string() + "\"");
    };
    for (const auto* s : {&sc.reference, &sc.examined})
        if (!s->phantom && !s->mesh.empty() && missing(s->mesh))
            return s->mesh.string() +
                   (s->needs_data_root ? " (shared data; give --data-root or GLINT_DATA)" : "");
    if (!sc.truth_mask.empty() && missing(sc.truth_mask)) return sc.truth_mask.string();
    if (!sc.truth_pose_conf.empty() && missing(sc.truth_pose_conf))
        return sc.truth_pose_conf.string();
    return "";
}

ScenarioOutcome run_scenario(const Scenario& sc, const ScenarioRunOptions& run) {
    const auto t0 = std::chrono::steady_clock::now();
    ScenarioOutcome out;
    out.name = sc.name;
    out.file = sc.file;
    if (const std::string missing = missing_input(sc); !missing.empty()) {
        // Scenarios tagged "data" use the shared data folder: its absence is a skip, not an
        // error. Any other missing input is an error.
        const bool shared = std::find(sc.tags.begin(), sc.tags.end(), "data") != sc.tags.end();
        if (!shared)
            throw InputError("scenario \"" + sc.file.string() + "\": input not found: " + missing);
        out.skipped = true;
        out.skip_reason = "input not found: " + missing;
        return out;
    }
    if (run.observer.stage) run.observer.stage("load");
    const ScenarioMeshes meshes = build_scenario_meshes(sc);
    out.reference_vertices = meshes.reference.vertex_count();

    RunRecord record;
    InspectOptions options = detail::scenario_inspect_options(sc, run, meshes, record);
    if (sc.asymmetry.enabled) {
        const std::vector<Region> regions =
            detail::run_asymmetry(sc, run, meshes, options, std::move(record), out);
        check_expect(sc.expect, regions, out);
        check_asymmetry_expect(sc.expect.asymmetry, *out.asymmetry, out.failures);
        out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return out;
    }
    if (!run.output_root.empty()) {
        const SurfaceSource& e = sc.examined;
        // A pair generator's scan of the reference's object is a second acquisition of it,
        // not the reference's surface edited.
        const bool scanned = sc.resample_volume || sc.reference.acquisition.any();
        const char* derived = !scanned                  ? "derived from the reference"
                              : sc.reference.scan_as_ct ? "a CT scan of the reference's solid"
                                                        : "a scan of the reference's volume";
        record.inputs.push_back({"examined", sc.examined_derived ? fs::path() : e.mesh,
                                 sc.examined_derived ? derived : detail::describe_source(e),
                                 meshes.examined.vertex_count(), meshes.examined.triangle_count()});
        add_truth_scalars(meshes, options.exports);
    }
    const Inspection inspection =
        inspect(meshes.reference, meshes.examined, options, record, run.observer);
    const AnalysisResult& result = inspection.analysis;
    out.fit_mode = to_string(result.fit.mode);
    if (meshes.has_truth_pose)
        out.pose =
            pose_error(result.fit.reference_from_examined, meshes.true_reference_from_examined,
                       result.fit.examined_scale, meshes.true_examined_scale);
    out.views = result.sweep.plan.views.size();
    out.output = inspection.output;
    const ZoomDecision& z0 = result.decisions.front();
    out.regions = z0.regions.regions.size();
    const auto& regions = z0.regions.regions;
    if (!regions.empty()) {
        // Surface gone is listed first (decision/regions.h); the largest is by area.
        out.largest_kind = to_string(
            std::max_element(regions.begin(), regions.end(), [](const Region& a, const Region& b) {
                return a.area < b.area;
            })->kind);
        const Region& first = regions.front();
        out.first_kind = first.is_hole_loss() ? "surface gone" : to_string(first.kind);
        out.first_area = first.area;
        out.first_volume = first.volume;
    }
    out.coverage = result.sweep.zooms.front().coverage.fraction;
    out.compared = z0.comparison.fraction;
    out.threshold_deg = z0.normal.value;
    out.warnings = result.warnings;
    score_outcome(sc, meshes, result, out);
    check_expect(sc.expect, z0.regions.regions, out);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace glint
