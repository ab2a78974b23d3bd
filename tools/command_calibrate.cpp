// glint calibrate SCENARIO -o calibration.json: the zoom at which an expert's referential
// deformation stops showing; `glint sweep --calibration` then flags only larger ones.
#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/units.h"
#include "report/calibration_file.h"
#include "scenario/scenario.h"
#include "tools/command.h"
#include "tools/option_flags.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

namespace glint::cli::calibrate_command {
namespace {

struct CalibrateArgs {
    std::string scenario;
    std::string data_root;
    CalibrationOptions options;
    std::string output;
    bool print = false;
};

void run(const CalibrateArgs& a) {
    a.options.validate();
    std::string root = a.data_root;
    if (root.empty())
        if (const char* env = std::getenv("GLINT_DATA")) root = env;
    const Scenario sc = load_scenario(a.scenario, root);
    if (a.print) {
        print_options(sc.analysis);
        return;
    }
    guard_outputs({a.output}, {a.scenario, sc.reference.mesh, sc.examined.mesh});
    const ScenarioMeshes meshes = build_scenario_meshes(sc);
    AnalysisOptions analysis = sc.analysis;
    if (analysis.fit.mode == FitMode::Truth) {
        analysis.fit.truth = meshes.true_reference_from_examined;
        analysis.fit.truth_scale = meshes.true_examined_scale;
    }
    const Calibration c =
        calibrate(meshes.reference, meshes.examined, analysis, a.options,
                  sc.name + (sc.description.empty() ? "" : ": " + sc.description));
    write_file_atomically(a.output, to_json(c));
    if (global_flags().json) {
        nlohmann::json j = nlohmann::json::parse(to_json(c));
        j["output"] = absolute_output(a.output);
        std::cout << json_text(j, 2) << '\n';
    } else {
        const std::string unit = !analysis.units.unit.empty()
                                     ? canonical_unit(analysis.units.unit)
                                     : canonical_unit(meshes.reference.unit);
        for (const auto& r : c.ladder)
            std::printf("  footprint %s/px: %zu region(s), strongest mean angle %.2f°\n",
                        with_unit(r.footprint, unit, 1, "%8.4f").c_str(), r.regions,
                        r.max_angle_deg);
        if (c.found)
            std::printf(
                "calibrated: the referential deformation hides from %s per pixel at %.1f°; wrote %s\n",
                with_unit(c.footprint, unit, 1, "%.4f").c_str(), c.threshold_deg, a.output.c_str());
    }
    if (!c.found)
        throw CheckFailed(
            "the referential deformation shows even at the coarsest footprint; raise --coarsest");
}

void setup(CLI::App& app) {
    static CalibrateArgs a;
    auto* cmd = app.add_subcommand(
        "calibrate", "Find the zoom at which a referential deformation no longer shows");
    cmd->add_option("SCENARIO", a.scenario,
                    "Scenario holding the referential case (surface + referential deformation)")
        ->required();
    cmd->add_option("--data-root", a.data_root,
                    "Where scenario mesh paths are looked up (default: $GLINT_DATA)");
    cmd->add_option("--threshold-deg", a.options.threshold_deg,
                    "Angle a deformation must reach to show")
        ->capture_default_str();
    cmd->add_option("--finest", a.options.finest,
                    "Finest footprint of the ladder (default: radius/256)");
    cmd->add_option("--coarsest", a.options.coarsest,
                    "Coarsest footprint of the ladder (default: radius/3)");
    cmd->add_option("--step", a.options.step, "Ratio between ladder rungs")->capture_default_str();
    cmd->add_option("-o,--output", a.output, "calibration.json")->required();
    add_print_options_flag(*cmd, a.print);
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(75, setup);

}  // namespace
}  // namespace glint::cli::calibrate_command
