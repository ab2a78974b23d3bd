// glint asymmetry MESH -o OUT: left–right asymmetry of one surface (analysis/asymmetry.h): the
// symmetry plane, then the surface swept against its own mirror image, findings side by side.
#include "analysis/asymmetry.h"
#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/roi.h"
#include "mesh/units.h"
#include "report/asymmetry_json.h"
#include "report/asymmetry_run.h"
#include "report/inspect.h"
#include "report/orientation.h"
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
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint::cli::asymmetry_command {
namespace {

namespace fs = std::filesystem;

struct AsymmetryArgs {
    std::string mesh;
    SurfaceOptions surface;
    InspectOptions options;
    std::string plane;
    std::string output;
    bool force = false;
};

double axis_angle_deg(const Vec3d& n, int axis) {
    return std::acos(std::min(1.0, std::abs(n[axis]))) * 180.0 / std::numbers::pi;
}

void print_plane(const SymmetryPlaneResult& r, const std::string& u) {
    const SymmetryPlane& p = r.plane;
    std::printf(
        "symmetry plane (%s): normal (%.5f, %.5f, %.5f), offset %s, %.3f° from the x "
        "axis\n  %s\n",
        r.source.c_str(), p.normal.x(), p.normal.y(), p.normal.z(), with_unit(p.offset, u).c_str(),
        axis_angle_deg(p.normal, 0), r.verdict.c_str());
}

void print_findings(const nlohmann::json& a, std::size_t regions) {
    // note: the floor's words are report.json's (report/asymmetry_json.h), as report.html's
    const auto& fl = a["symmetry_floor"];
    std::printf("rest of the surface: %s\n", fl["spread_text"].get<std::string>().c_str());
    if (fl.contains("min_detectable_text"))
        std::printf("smallest one-sided change that can be told from it: %s\n",
                    fl["min_detectable_text"].get<std::string>().c_str());
    std::printf("%zu finding(s) from %zu region(s); %s\n", a["findings"].size(), regions,
                std::string(kOneScanCaveat).c_str());
    for (const auto& f : a["findings"]) std::printf("  %s\n", f["text"].get<std::string>().c_str());
}

void run(AsymmetryArgs& a) {
    AsymmetryOptions options = take_asymmetry_options(
        a.options.analysis,
        a.plane.empty() ? std::nullopt : std::optional(parse_plane_spec(a.plane)));
    a.options.exports.output = a.output;
    a.options.exports.replace_existing = a.force;
    a.options.validate();
    options.validate();
    guard_outputs({a.output}, {a.mesh});
    StageProgress progress;
    progress.stage("load");
    RunInput input = load_run_input("reference", a.mesh, a.surface);
    if (auto& roi = options.plane.registration.roi; roi && roi->needs_mask())
        read_roi_mask(*roi, input.mesh.vertex_count());
    progress.stage("symmetry plane");
    AsymmetryPlane plane = prepare_asymmetry(input.mesh, options);
    const std::string& unit = input.mesh.unit;
    if (plane.mirror.triangles.empty()) {
        progress.finish();
        print_warnings(input.warnings);
        // The result (the plane and its verdict) before the check fails (tools/main.cpp).
        if (global_flags().json)
            std::cout << json_text(
                             nlohmann::json{{"asymmetry",
                                             {{"plane", nlohmann::json::parse(symmetry_plane_json(
                                                            plane.plane, unit))}}}},
                             2)
                      << '\n';
        else print_plane(plane.plane, unit);
        throw CheckFailed("\"" + a.mesh + "\": " + plane.plane.verdict +
                          "; no asymmetry is reported and nothing was written (the best plane "
                          "found, given by hand, runs anyway: --plane \"" +
                          to_string(plane.plane.plane) + "\")");
    }
    RunRecord record{.command_line = global_flags().command_line};
    record.add(input);
    const Orientation orientation =
        resolve_orientation(parse_space(input.record.space), a.options.exports.up);
    const SymmetryPlaneResult fitted = plane.plane;
    AnalysisObserver observer;
    observer.stage = [](std::string_view) { give_back_free_memory(); };
    progress.listen(observer);
    const AsymmetryInspection run =
        inspect_asymmetry(input.mesh, std::move(plane), a.options, record, orientation, observer);
    const Inspection& result = run.inspection;
    progress.finish();
    print_warnings(run.warnings);
    if (global_flags().json) {
        nlohmann::json j = nlohmann::json::parse(result.report_json);
        j["output"] = absolute_output(result.output);
        std::cout << json_text(j, 2) << '\n';
        return;
    }
    const nlohmann::json report = nlohmann::json::parse(run.json);
    print_plane(fitted, result.analysis.unit);
    const auto& d = result.analysis.decisions;
    print_findings(report, d.empty() ? 0 : d[0].regions.regions.size());
    std::printf("atlas (field asymmetry), %sreport in %s\n",
                a.options.exports.write_pictures ? "pictures and " : "no pictures, ",
                result.output.string().c_str());
}

void setup(CLI::App& app) {
    static AsymmetryArgs a;
    auto* cmd = app.add_subcommand(
        "asymmetry",
        "Left-right asymmetry of one surface: fit its symmetry plane, compare each side with "
        "the mirror of the other");
    cmd->add_option("MESH", a.mesh, "Mesh, or volume with --iso")->required();
    add_surface_flags(*cmd, a.surface);
    cmd->add_option("--plane", a.plane,
                    "The symmetry plane by hand instead of fitted: x=C (or y=, z=), "
                    "point=x,y,z;normal=x,y,z, or landmarks=x,y,z/x,y,z/x,y,z");
    add_analysis_flags(*cmd, a.options.analysis,
                       kFitGroup | kSweepGroup | kDecisionGroup | kUnitGroup);
    add_option_flags(*cmd, a.options.exports, export_option_table(), kExportGroup);
    cmd->add_option("-o,--output", a.output, "Output folder (written complete or not at all)")
        ->required();
    cmd->add_flag("--force", a.force,
                  "Replace an existing output folder (only once the new results are complete)");
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(62, setup);

}  // namespace
}  // namespace glint::cli::asymmetry_command
