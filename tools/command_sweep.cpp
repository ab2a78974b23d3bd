// glint sweep REF EXA …: the rotary scan end to end: fit, sweep, compare, atlas, exports.
#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/geometry.h"
#include "mesh/io.h"
#include "scanner/calibrate.h"
#include "scanner/fit.h"
#include "scanner/output_folder.h"
#include "scanner/report.h"
#include "scanner/sweep.h"
#include "tools/command.h"
#include "tools/fit_options.h"
#include "tools/progress.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace glint::cli {
namespace {

namespace fs = std::filesystem;

struct SweepArgs {
    std::string reference;
    std::string examined;
    FitArgs fit;
    std::string plan = "rotary";
    double azimuth_step = 30.0;
    std::vector<double> elevations{-60, -30, 0, 30, 60};
    std::vector<double> zooms;
    std::string roi;
    int size = 256;
    int supersample = 2;
    double threshold_deg = 0.0;
    double noise_k = 6.0;
    double min_threshold_deg = 2.0;
    double max_incidence = 75.0;
    std::string backend = "auto";
    std::string metric = "angle";
    std::string device;
    bool no_views = false;
    bool no_exr = false;
    std::string calibration;
    std::string output;
};

void print_summary(const SweepResult& r, const fs::path& out) {
    const char* unit = r.options.metric == Metric::RgbAbs ? " (rgb)" : "°";
    for (std::size_t z = 0; z < r.zooms.size(); ++z) {
        const auto& zr = r.zooms[z];
        std::printf("zoom %zu: footprint %.4g/px (%d px), coverage %.1f%%, threshold %.2f%s (%s), %zu region(s)\n", z,
                    r.plan.footprints[z], r.plan.sizes[z], 100.0 * zr.coverage, zr.threshold_deg, unit,
                    zr.threshold_rule == "given" ? "given" : "noise floor", zr.regions.regions.size());
        for (const auto& g : zr.regions.regions)
            std::printf("  region %d: %s, area %.4g, max %.2f%s, mean %.2f%s, max depth %+.4g, centroid (%.3f, %.3f, %.3f)\n",
                        g.id, to_string(g.kind).c_str(), g.area, g.max_angle_deg, unit, g.mean_angle_deg, unit,
                        g.max_depth, g.centroid.x(), g.centroid.y(), g.centroid.z());
    }
    std::printf("%zu views in %.1f s (%s on %s); atlas, views, mosaics and report in %s\n", r.views.size(),
                r.total_seconds, to_string(r.renderer.backend).c_str(), r.renderer.device_name.c_str(),
                out.string().c_str());
}

void run(const SweepArgs& a) {
    SweepOptions options;
    parse_plan_kind(a.plan, options.plan);
    options.plan.azimuth_step_deg = a.azimuth_step;
    options.plan.elevations_deg = a.elevations;
    options.plan.footprints = a.zooms;
    options.plan.size = a.size;
    if (!a.roi.empty()) options.plan.roi = parse_roi(a.roi);
    options.render.backend = parse_backend(a.backend);
    options.render.device = a.device;
    options.render.supersample = a.supersample;
    if (a.threshold_deg > 0) options.threshold_deg = a.threshold_deg;
    options.noise_k = a.noise_k;
    options.min_threshold_deg = a.min_threshold_deg;
    options.max_incidence_deg = a.max_incidence;
    options.metric = parse_metric(a.metric);
    if (!a.calibration.empty()) {
        // The calibrated zoom and threshold: only deformations larger than the referential
        // one show.
        const Calibration c = read_calibration(a.calibration);
        options.plan.footprints = {c.footprint};
        options.threshold_deg = c.threshold_deg;
    }
    options.validate();

    const LoadedMesh ref = load_mesh(a.reference);
    const LoadedMesh exa = load_mesh(a.examined);
    OutputFolder folder(a.output);  // checks the output location before the long work

    ReportContext context;
    context.command_line = global_flags().command_line;
    context.inputs.push_back({"reference", a.reference, "", ref.mesh.vertex_count(), ref.mesh.triangle_count()});
    context.inputs.push_back({"examined", a.examined, "", exa.mesh.vertex_count(), exa.mesh.triangle_count()});
    for (const auto* r : {&ref.report, &exa.report})
        for (const auto& w : r->warnings) context.warnings.push_back(r->path.string() + ": " + w);

    const FitOutcome fit = fit_examined(ref.mesh, exa.mesh, to_request(a.fit));
    if (!fit.converged)
        throw InputError("registration of \"" + a.examined + "\" onto \"" + a.reference +
                         "\" did not converge (" + (fit.warnings.empty() ? std::string("no reason given") : fit.warnings.back()) +
                         "); the meshes may not overlap: give --fit or start from landmarks with glint register");
    context.fit_json = fit.json;
    for (const auto& w : fit.warnings) context.warnings.push_back(w);
    if (!a.fit.fit_file.empty()) context.inputs.push_back({"fit", a.fit.fit_file, "", 0, 0});
    if (!a.calibration.empty()) context.inputs.push_back({"calibration", a.calibration, "", 0, 0});
    Mesh fitted = exa.mesh;
    transform_mesh(fitted, fit.reference_from_examined);
    context.distance = signed_distances(ref.mesh, fitted);

    const SweepPlan plan = make_sweep_plan(ref.mesh, options.plan);
    SweepExporter exporter(folder, plan,
                           SweepExporter::Options{.write_views = !a.no_views, .write_exr = !a.no_exr});
    ProgressBar bar("sweep", plan.views.size());
    std::size_t done = 0;
    auto export_view = exporter.observer();
    const SweepResult result = run_sweep(ref.mesh, fitted, plan, options,
                                         [&](const PlannedView& v, const Frame& rf, const Frame& ef, const DeviationMap& d) {
                                             export_view(v, rf, ef, d);
                                             bar.update(++done);
                                         },
                                         context.distance);
    bar.finish();
    exporter.finish();
    write_sweep_outputs(folder, ref.mesh, result, context);
    folder.commit();
    if (global_flags().json) std::cout << sweep_report_json(ref.mesh, result, context);
    else if (!global_flags().quiet) print_summary(result, folder.target());
}

void setup(CLI::App& app) {
    static SweepArgs a;
    auto* cmd = app.add_subcommand("sweep", "Fit, sweep the virtual rotary scanner, compare and write the damage atlas");
    cmd->add_option("REF", a.reference, "Reference mesh")->required();
    cmd->add_option("EXA", a.examined, "Examined mesh")->required();
    add_fit_options(*cmd, a.fit);
    cmd->add_option("--plan", a.plan, "rotary | sphere:N")->capture_default_str();
    cmd->add_option("--azimuth-step", a.azimuth_step, "Rotary: azimuth step, degrees")->capture_default_str();
    cmd->add_option("--elevations", a.elevations, "Rotary: elevation rings, degrees")->delimiter(',')->capture_default_str();
    cmd->add_option("--zoom", a.zooms, "Zoom levels as footprints (mesh units per pixel); default: frame in --size px")
        ->delimiter(',');
    cmd->add_option("--roi", a.roi, "Analyse part of the surface: sphere:x,y,z,r or box:x0,y0,z0,x1,y1,z1");
    cmd->add_option("--size", a.size, "Image size framing the whole mesh (when no --zoom)")->capture_default_str();
    cmd->add_option("--supersample", a.supersample, "s×s sub-samples per pixel (footprint averaging)")->capture_default_str();
    cmd->add_option("--threshold-deg", a.threshold_deg, "Damage threshold in degrees (default: the run's noise floor)");
    cmd->add_option("--noise-k", a.noise_k, "Noise floor: median + k·1.4826·MAD")->capture_default_str();
    cmd->add_option("--min-threshold-deg", a.min_threshold_deg, "Noise floor never below this")->capture_default_str();
    cmd->add_option("--max-incidence", a.max_incidence, "Coverage rule: max incidence angle, degrees")->capture_default_str();
    cmd->add_option("--backend", a.backend, "auto | vulkan | embree")->capture_default_str();
    cmd->add_option("--metric", a.metric,
                    "angle (degrees between normals) | rgb (the paper's 8-bit colour difference, 0-255; "
                    "thresholds then in colour units)")
        ->capture_default_str();
    cmd->add_option("--device", a.device, "Vulkan device name (substring)");
    cmd->add_flag("--no-views", a.no_views, "Do not write per-view PNG heat maps");
    cmd->add_flag("--no-exr", a.no_exr, "Do not write per-view EXR files");
    cmd->add_option("--calibration", a.calibration, "calibration.json from glint calibrate: its zoom and threshold")
        ->excludes("--zoom")
        ->excludes("--threshold-deg");
    cmd->add_option("-o,--output", a.output, "Output folder (written complete or not at all)")->required();
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(60, setup);

}  // namespace
}  // namespace glint::cli
