#include "tools/analysis_flags.h"

#include "mesh/units.h"

#include <iostream>

namespace glint::cli {

void add_fit_flags(CLI::App& cmd, FitOptions& fit, const std::string& roi_flag, bool with_mode) {
    RegistrationOptions& r = fit.registration;
    if (with_mode) {
        auto* file = cmd.add_option_function<std::string>(
            "--fit",
            [&fit](const std::string& v) {
                fit.mode = FitMode::File;
                fit.fit_file = v;
            },
            "fit.json from glint register (examined → reference)");
        auto* reg = cmd.add_flag_callback(
            "--register", [&fit] { fit.mode = FitMode::Register; },
            "Fit the examined mesh now (robust ICP)");
        file->excludes(reg);
    }
    cmd.add_option_function<std::string>(
        "--loss", [&r](const std::string& v) { r.loss = parse_loss(v); },
        "Registration: robust loss cauchy | huber | tukey | none (default cauchy)");
    cmd.add_option_function<std::string>(
        roi_flag, [&r](const std::string& v) { r.roi = parse_roi(v); },
        "Registration: fit only on this stable region of the reference: sphere:x,y,z,r, box:x0,y0,z0,x1,y1,z1 or "
        "mask:FILE.ply[:SCALAR] (the reference's vertices, non-zero label or scalar inside)");
    cmd.add_flag("--symmetric", r.symmetric, "Registration: symmetric ICP (both directions)");
    cmd.add_option_function<std::string>(
        "--landmarks", [&fit](const std::string& v) { fit.landmarks_file = v; },
        "Registration: start from landmark pairs, JSON {\"pairs\": [{\"examined\": SIDE, \"reference\": SIDE}]}, "
        "SIDE = [x,y,z] or {\"view\": {\"azimuth\": A, \"elevation\": E, \"size\": N}, \"pixel\": [u,v]} (as glint pick)");
    cmd.add_option_function<std::string>(
        "--init", [&fit](const std::string& v) { fit.init_file = v; },
        "Registration: start from this fit.json");
    cmd.add_option("--samples", r.samples, "Registration: samples on the examined surface")
        ->capture_default_str();
    cmd.add_option("--max-iterations", r.max_iterations, "Registration: ICP iterations")
        ->capture_default_str();
    cmd.add_flag_callback(
        "--no-coarse", [&r] { r.coarse = false; },
        "Registration: skip the principal-axes hypotheses");
}

void add_sweep_flags(CLI::App& cmd, AnalysisOptions& o) {
    SweepOptions& s = o.sweep;
    DecisionOptions& d = o.decision;
    cmd.add_option_function<std::string>(
        "--plan", [&s](const std::string& v) { parse_plan_kind(v, s.plan); },
        "rotary | sphere:N (default rotary)");
    cmd.add_option("--azimuth-step", s.plan.azimuth_step_deg, "Rotary: azimuth step, degrees")
        ->capture_default_str();
    cmd.add_option("--elevations", s.plan.elevations_deg, "Rotary: elevation rings, degrees")
        ->delimiter(',')
        ->capture_default_str();
    cmd.add_option("--zoom", s.plan.footprints,
                   "Zoom levels as footprints (mesh units per pixel); default: frame in --size px")
        ->delimiter(',');
    cmd.add_option_function<std::string>(
        "--roi", [&s](const std::string& v) { s.plan.roi = parse_roi(v); },
        "Analyse part of the surface: sphere:x,y,z,r, box:x0,y0,z0,x1,y1,z1 or mask:FILE.ply[:SCALAR]");
    cmd.add_option("--size", s.plan.size, "Image size framing the whole mesh (when no --zoom)")
        ->capture_default_str();
    cmd.add_option("--supersample", s.render.supersample,
                   "s×s sub-samples per pixel (footprint averaging)")
        ->capture_default_str();
    std::string metrics;
    for (const auto& m : glint::metrics())
        metrics += (metrics.empty() ? "" : " | ") + std::string(m.name) + " (" +
                   std::string(m.description) + ")";
    cmd.add_option_function<std::string>(
        "--metric", [&s](const std::string& v) { s.metric = parse_metric(v); }, metrics);
    cmd.add_option_function<std::string>(
        "--backend", [&s](const std::string& v) { s.render.backend = parse_backend(v); },
        "auto | vulkan | embree (default auto)");
    cmd.add_option("--device", s.render.device, "Vulkan device name (substring)");
    cmd.add_option_function<std::string>(
        "--accumulate", [&s](const std::string& v) { s.accumulate = parse_accumulation(v); },
        "Compare and back-project on the GPU or the CPU: auto (GPU with Vulkan, unless per-view EXRs are "
        "written) | gpu | host (default auto)");
    cmd.add_option("--max-incidence", s.max_incidence_deg,
                   "Coverage rule: max incidence angle, degrees")
        ->capture_default_str();
    cmd.add_option_function<std::string>(
        "--rule", [&d](const std::string& v) { d.rule = parse_decision_rule(v); },
        "Decision: fused (normal-field and shape evidence) | normal (the paper's angle-only rule)");
    cmd.add_option_function<double>(
        "--threshold-deg", [&d](double v) { d.threshold = v; },
        "Normal evidence threshold in the metric's unit (default: the run's noise floor)");
    cmd.add_option("--noise-k", d.noise_k, "Normal floor: median + k·1.4826·MAD")
        ->capture_default_str();
    cmd.add_option("--min-threshold-deg", d.min_threshold, "Normal floor never below this")
        ->capture_default_str();
    cmd.add_option_function<double>(
        "--shape-threshold", [&d](double v) { d.shape_threshold = v; },
        "Shape evidence threshold, mesh units (default: the run's floor)");
    cmd.add_option("--min-region-vertices", d.min_region_vertices, "Smaller groups are dropped")
        ->capture_default_str();
}

void add_unit_flags(CLI::App& cmd, UnitOptions& units) {
    cmd.add_option("--unit", units.unit,
                   "Length unit of both meshes: " + known_units() +
                       " (default: what the files state; unknown lengths are printed as 'units')");
    cmd.add_flag("--allow-scale-mismatch", units.allow_scale_mismatch,
                 "Run even when the meshes' sizes differ by more than 5x (different units?)");
}

void add_print_options_flag(CLI::App& cmd, bool& print) {
    cmd.add_flag("--print-options", print,
                 "Print the resolved analysis options as JSON and stop (loads nothing)");
}

void print_options(const AnalysisOptions& options) { std::cout << to_json(options) << '\n'; }

}  // namespace glint::cli
