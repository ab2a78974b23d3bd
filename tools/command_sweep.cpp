// glint sweep REF EXA …: the rotary scan end to end (analysis/analysis.h): fit, distance,
// sweep, decision, exports.
#include "analysis/analysis.h"
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/units.h"
#include "report/calibration_file.h"
#include "report/finding.h"
#include "report/inspect.h"
#include "report/run_inputs.h"
#include "tools/command.h"
#include "tools/memory.h"
#include "tools/option_flags.h"
#include "tools/progress.h"
#include "tools/surface_flags.h"
#include "volume/load.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>

namespace glint::cli::sweep_command {
namespace {

namespace fs = std::filesystem;

struct SweepArgs {
    std::string reference;
    std::string examined;
    SurfaceOptions surface;
    InspectOptions options;
    std::string calibration;
    std::string output;
    bool print = false;
    bool force = false;
};

// "normal floor 2.00° (minimum), shape floor 0.012 mm (measured)": each floor with how it was
// obtained (decision/decision.h FloorSource).
std::string floors_line(const ZoomDecision& d, const MetricDescriptor& m, const std::string& u) {
    // note: at a chosen scale the normal evidence is the tilt over that scale, in degrees.
    const std::string sym = d.scale.radius > 0 ? "°" : std::string(m.symbol);
    char b[200];
    std::snprintf(b, sizeof b, "normal floor %.2f%s (%s)", d.normal.value, sym.c_str(),
                  to_string(d.normal.source).c_str());
    std::string line = b;
    if (d.rule == DecisionRule::Fused)
        line += ", shape floor " + with_unit(d.shape.value, u, 1, "%.3g") + " (" +
                to_string(d.shape.source) + ")";
    return line;
}

void print_summary(const Inspection& inspection, bool pictures) {
    const AnalysisResult& r = inspection.analysis;
    const nlohmann::json report = nlohmann::json::parse(inspection.report_json);
    const MetricDescriptor& m = describe(r.sweep.options.metric);
    const std::string sym(m.symbol);
    const std::string& u = r.unit;
    std::printf("unit %s; reference %s across, examined %s\n",
                u.empty() ? "unknown (the files state none; --unit states it)" : u.c_str(),
                with_unit(r.units.reference_size, u).c_str(),
                with_unit(r.units.examined_size, u).c_str());
    for (std::size_t z = 0; z < r.decisions.size(); ++z) {
        const auto& d = r.decisions[z];
        std::printf("zoom %zu: footprint %s/px (%d px), coverage %.1f%%, %s, %zu region(s)\n", z,
                    with_unit(r.sweep.plan.footprints[z], u).c_str(), r.sweep.plan.sizes[z],
                    100.0 * r.sweep.zooms[z].coverage.fraction, floors_line(d, m, u).c_str(),
                    d.regions.regions.size());
        if (!d.scale.text.empty()) std::printf("  %s\n", d.scale.text.c_str());
        const Comparison& c = d.comparison;
        const auto pct = [&](double a) {
            return c.reference_area > 0 ? 100.0 * a / c.reference_area : 0.0;
        };
        if (c.fraction < 1.0)
            std::printf(
                "  compared %.1f%% of the reference's area; not compared: %.1f%% not reached by "
                "the examined surface, %.1f%% along the reference's borders, %.1f%% along the "
                "examined surface's borders, %.1f%% below the scans' resolution (thin plates and "
                "narrow gaps)\n",
                100.0 * c.fraction, pct(c.not_reached_area), pct(c.reference_border_area),
                pct(c.examined_border_area), pct(c.below_resolution_area));
        if (c.dropouts > 0)
            std::printf(
                "  the examined surface is a one-view scan (its normals within %.0f° of one "
                "direction): %zu gone patch(es), %.1f%% of the reference, faced beyond %.0f° are "
                "scanner dropouts, not compared\n",
                c.scan_view ? c.scan_view->cone_deg : 0.0, c.dropouts, pct(c.dropout_area),
                kGrazingDeg);
        if (c.beyond_view > 0)
            std::printf(
                "  %zu gone patch(es), %.1f%% of the reference, reach beyond the examined scan's "
                "field of view (its volume's grid or surface ROI): not reached\n",
                c.beyond_view, pct(c.beyond_view_area));
        // Each region in words (report.json's "finding", report/finding.h); the method's
        // figures (angles, floors, evidence) are in report.json.
        const nlohmann::json& found = report["zooms"][z]["regions"];
        for (std::size_t k = 0; k < d.regions.regions.size(); ++k) {
            const Region& g = d.regions.regions[k];
            const std::string words = k < found.size() && found[k].contains("finding")
                                          ? found[k]["finding"].get<std::string>()
                                          : to_string(g.kind);
            // How strongly it stands out (decision.cpp state_significance).
            char stands[96] = "";
            if (std::isfinite(g.z))
                std::snprintf(stands, sizeof stands, "; %.*f spreads of the undamaged surface, %s",
                              g.z < 100 ? 1 : 0, g.z, significance_text(g.p_value).c_str());
            // Found over a wider disc than the scale chosen (decision.cpp search_wider).
            char wider[96] = "";
            if (g.scale_radius > d.scale.radius && d.scale.radius > 0)
                std::snprintf(wider, sizeof wider,
                              "; found over a radius of %.3g %s (a wider rung)", g.scale_radius,
                              u.empty() ? "units" : u.c_str());
            std::printf("  region %d: %s%s%s; centroid (%.3f, %.3f, %.3f) %s\n", g.id,
                        words.c_str(), stands, wider, g.centroid.x(), g.centroid.y(),
                        g.centroid.z(), u.empty() ? "units" : u.c_str());
        }
    }
    std::printf("%zu views in %.1f s (%s on %s); atlas, %sreport in %s (open %s in a browser)\n",
                r.sweep.views.size(), inspection.total_seconds,
                to_string(r.sweep.renderer.backend).c_str(), r.sweep.renderer.device_name.c_str(),
                pictures ? "pictures and " : "no pictures, ", inspection.output.string().c_str(),
                (inspection.output / "report.html").string().c_str());
}

void run(SweepArgs& a) {
    InspectOptions& options = a.options;
    if (!a.calibration.empty()) {
        // The calibrated zoom and threshold: only deformations larger than the referential
        // one show.
        const Calibration c = read_calibration(a.calibration);
        options.analysis.sweep.plan.footprints = {c.footprint};
        options.analysis.decision.threshold = c.threshold_deg;
    }
    options.exports.output = a.output;
    options.exports.replace_existing = a.force;
    options.validate();
    if (a.print) {
        print_options(options.analysis, options.exports);
        return;
    }
    const FitOptions& fit = options.analysis.fit;
    guard_outputs({a.output}, {a.reference, a.examined, fit.fit_file, fit.landmarks_file,
                               fit.init_file, a.calibration});
    StageProgress progress;
    progress.stage("load");
    auto [ref, exa] = load_run_pair(
        a.reference, a.examined, a.surface,
        [&, n = std::size_t{0}](std::string_view) mutable { progress.items(++n, 2); });
    RunRecord record{.command_line = global_flags().command_line};
    record.add(ref);
    record.add(exa);
    if (!options.analysis.fit.fit_file.empty())
        record.add_file("fit", options.analysis.fit.fit_file);
    if (!a.calibration.empty()) record.add_file("calibration", a.calibration);

    AnalysisObserver observer;
    observer.stage = [](std::string_view) { give_back_free_memory(); };
    progress.listen(observer);
    const Inspection result = inspect(ref.mesh, std::move(exa.mesh), options, record, observer);
    progress.finish();
    print_warnings(result.analysis.warnings);
    if (global_flags().json) {
        // report.json's content and where it was written (the folder is not in the file: a
        // folder may be moved).
        nlohmann::json j = nlohmann::json::parse(result.report_json);
        j["output"] = absolute_output(result.output);
        std::cout << json_text(j, 2) << '\n';
    } else print_summary(result, options.exports.write_pictures);
}

void setup(CLI::App& app) {
    static SweepArgs a;
    auto* cmd = app.add_subcommand(
        "sweep", "Fit, sweep the virtual rotary scanner, compare and write the damage atlas");
    cmd->add_option("REF", a.reference, "Reference mesh, or volume with --iso")->required();
    cmd->add_option("EXA", a.examined, "Examined mesh, or volume with --iso")->required();
    add_surface_flags(*cmd, a.surface);
    add_fit_mode_flags(*cmd, a.options.analysis.fit);
    add_analysis_flags(*cmd, a.options.analysis, kFitGroup | kSweepGroup | kDecisionGroup);
    add_option_flags(*cmd, a.options.exports, export_option_table(), kExportGroup);
    cmd->add_option("--calibration", a.calibration,
                    "calibration.json from glint calibrate: its zoom and threshold")
        ->excludes("--zoom")
        ->excludes("--threshold-deg");
    add_analysis_flags(*cmd, a.options.analysis, kUnitGroup);
    cmd->add_option("-o,--output", a.output, "Output folder (written complete or not at all)")
        ->required();
    cmd->add_flag("--force", a.force,
                  "Replace an existing output folder (only once the new results are complete)");
    add_print_options_flag(*cmd, a.print);
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(60, setup);

}  // namespace
}  // namespace glint::cli::sweep_command
