// glint register REF EXA … -o fit.json: rigid fit of the examined mesh onto the reference
// (analysis/fit.h: the same fit `glint sweep --register` and scenarios run).
#include "analysis/fit.h"
#include "analysis/units.h"
#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/file_set.h"
#include "mesh/io.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/units.h"
#include "mesh/write.h"
#include "tools/command.h"
#include "tools/option_flags.h"
#include "tools/surface_flags.h"
#include "volume/load.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

namespace glint::cli::register_command {
namespace {

namespace fs = std::filesystem;

struct RegisterArgs {
    std::string reference;
    std::string examined;
    SurfaceOptions surface;
    AnalysisOptions options;  ///< its fit and units (the registry's flags bind the whole)
    std::string roi_mask;
    std::string output;
    std::string apply;
};

void print_result(const RegistrationResult& r, const std::string& output, const std::string& unit) {
    std::printf(
        "%s after %d iterations (%s start): rotation %.6f°, translation (%.6g, %.6g, %.6g) %s, RMS %s, "
        "inliers %.1f%%, overlap %.1f%%; wrote %s\n",
        r.converged ? "converged" : "did NOT converge", r.iterations, r.coarse.c_str(),
        rotation_angle_deg(r.reference_from_examined), r.reference_from_examined.translation().x(),
        r.reference_from_examined.translation().y(), r.reference_from_examined.translation().z(),
        unit.empty() ? "units" : unit.c_str(), with_unit(r.rms, unit).c_str(),
        100 * r.inlier_fraction, 100 * r.overlap, output.c_str());
    if (r.examined_scale != 1.0)
        std::printf(
            "  examined scale %.6f ± %.6f (similarity fit: the examined surface × this, "
            "then the motion)\n",
            r.examined_scale, r.scale_uncertainty);
    if (!r.converged) std::printf("  %s\n", r.termination_detail.c_str());
}

void run(RegisterArgs& a) {
    FitOptions& fit = a.options.fit;
    fit.mode = FitMode::Register;
    if (!a.roi_mask.empty()) fit.registration.roi = parse_roi("mask:" + a.roi_mask);
    fit.validate();
    a.options.units.validate();
    if (!a.apply.empty()) {
        if (!is_writable_mesh_path(a.apply))
            throw InputError("--apply \"" + a.apply + "\": unknown extension \"" +
                             fs::path(a.apply).extension().string() + "\", expected " +
                             kWritableMeshExtensions + " (nothing was written)");
        if (fs::path(a.apply) == fs::path(a.output))
            throw InputError("--apply \"" + a.apply + "\" is the -o file; expected two files");
    }
    guard_outputs({a.output, a.apply}, {a.reference, a.examined, fit.fit_file, fit.landmarks_file,
                                        fit.init_file, a.roi_mask});
    const LoadedSurface ref = load_surface(a.reference, a.surface);
    LoadedSurface exa = load_surface(a.examined, a.surface);
    // Sizes checked before the fit; files in two stated units are fitted in the reference's.
    const UnitResolution units = resolve_units(ref.mesh, exa.mesh, a.options.units);
    scale_to_analysis_unit(exa.mesh, units);
    // Warnings with --quiet too (tools/command.h print_warnings): no chatter.
    print_warnings(units.warnings);
    if (fit.registration.fit_scale) fit.registration.initial_scale *= starting_scale(units);
    const FitOutcome outcome = fit_examined(ref.mesh, exa.mesh, fit);
    const RegistrationResult& r = *outcome.registration;
    if (r.converged) print_warnings(outcome.warnings);  // a scale the rigid fit left
    FileSet files;  // fit.json and the fitted mesh appear together or not at all
    files.add(a.output, outcome.json);
    if (!a.apply.empty()) {
        Mesh moved = exa.mesh;
        apply_fit(moved, outcome);
        files.add(a.apply, [&](const fs::path& temp) { write_mesh(moved, temp); });
    }
    files.commit();
    if (global_flags().json) {
        nlohmann::json j = nlohmann::json::parse(outcome.json);
        j["output"] = absolute_output(a.output);
        if (!a.apply.empty()) j["applied"] = absolute_output(a.apply);
        std::cout << json_text(j, 2) << '\n';
    } else print_result(r, a.output, units.unit);
    if (!r.converged) throw CheckFailed("registration did not converge: " + r.termination_detail);
}

void setup(CLI::App& app) {
    static RegisterArgs a;
    auto* cmd =
        app.add_subcommand("register", "Fit the examined mesh onto the reference (robust ICP)");
    cmd->add_option("REF", a.reference, "Reference mesh, or volume with --iso")->required();
    cmd->add_option("EXA", a.examined, "Examined mesh, or volume with --iso")->required();
    add_surface_flags(*cmd, a.surface);
    add_analysis_flags(*cmd, a.options, kFitGroup | kUnitGroup);
    cmd->add_option("--roi-mask", a.roi_mask,
                    "Fit only where FILE.ply[:SCALAR] (the reference's vertices) has a "
                    "non-zero label (or scalar); the same as --fit-roi mask:FILE[:SCALAR]")
        ->excludes("--fit-roi");
    // note: `register --roi` was the fit region before the flags came from one registry, where
    // --roi is the analysed region; the old spelling says so instead of meaning something else.
    cmd->add_option_function<std::string>(
           "--roi",
           [](const std::string&) {
               throw InputError("register: --roi is now --fit-roi (the region the fit uses)");
           },
           "Renamed: --fit-roi")
        ->group("");
    cmd->add_option("-o,--output", a.output, "fit.json")->required();
    cmd->add_option("--apply", a.apply,
                    "Also write the fitted examined mesh (.ply, .vtk, .vtp, .stl, .obj, .off)");
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(40, setup);

}  // namespace
}  // namespace glint::cli::register_command
