// glint compare FRAME_A FRAME_B -o diff.exr|png: per-pixel comparison of two frames rendered
// earlier by `glint render` (EXR), same size and view.
#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "report/frame_file.h"
#include "report/images.h"
#include "scanner/compare.h"
#include "scanner/metric.h"
#include "tools/command.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

namespace glint::cli::compare_command {
namespace {

struct CompareArgs {
    std::string reference;
    std::string examined;
    std::string output;
    float min_coverage = 0.999f;
    double color_max_deg = 20.0;
};

void run(const CompareArgs& a) {
    // A share above 1 compared no pixel and still exited 0; NaN drew an empty scale (issue 52).
    if (!(a.min_coverage >= 0.0f && a.min_coverage <= 1.0f))
        throw InputError("--min-coverage = " + std::to_string(a.min_coverage) +
                         ": expected a share of the pixel in [0, 1]");
    if (!(a.color_max_deg > 0 && std::isfinite(a.color_max_deg)))
        throw InputError("--color-max = " + std::to_string(a.color_max_deg) +
                         ": expected finite degrees > 0");
    guard_outputs({a.output}, {a.reference, a.examined});
    const Frame ref = read_frame_exr(a.reference);
    const Frame exa = read_frame_exr(a.examined);
    CompareOptions options;
    options.min_coverage = a.min_coverage;
    const DeviationMap d =
        compare_frames(frame_view(ref), frame_view(exa), options, Metric::RgbAbs);
    const std::string ext = std::filesystem::path(a.output).extension().string();
    if (ext == ".exr") {
        std::vector<float> sil(d.silhouette.begin(), d.silhouette.end());
        write_exr_channels(a.output, d.width, d.height,
                           {"angle_deg", "signed_depth", "rgb_abs", "silhouette"},
                           {&d.angle_deg, &d.signed_depth, &d.value, &sil},
                           {{"reference", a.reference},
                            {"examined", a.examined},
                            {"silhouette_codes", "0 same, 1 reference only, 2 examined only"}});
    } else if (ext == ".png") {
        ColorScale scale;
        scale.high = a.color_max_deg;
        write_heatmap_png({d.width, d.height, d.angle_deg}, scale, "angle deviation", a.output);
    } else {
        throw InputError("output \"" + a.output +
                         "\": expected .exr (numbers) or .png (heat map), found '" + ext + "'");
    }
    const nlohmann::json j = {
        {"compared_pixels", d.compared},      {"reference_only", d.reference_only},
        {"examined_only", d.examined_only},   {"max_angle_deg", d.max_angle_deg},
        {"mean_angle_deg", d.mean_angle_deg}, {"output", absolute_output(a.output)}};
    if (global_flags().json) std::cout << json_text(j, 2) << '\n';
    else
        std::cout << "compared " << d.compared << " pixels: max " << d.max_angle_deg << "°, mean "
                  << d.mean_angle_deg << "°; silhouette: " << d.reference_only
                  << " reference only, " << d.examined_only << " examined only; wrote " << a.output
                  << '\n';
}

void setup(CLI::App& app) {
    static CompareArgs args;
    auto* cmd = app.add_subcommand("compare",
                                   "Compare two frames rendered earlier (EXR from glint render)");
    cmd->add_option("FRAME_A", args.reference, "Reference frame (.exr)")->required();
    cmd->add_option("FRAME_B", args.examined, "Examined frame (.exr), same view and size")
        ->required();
    cmd->add_option("-o,--output", args.output,
                    "diff.exr (angle, signed depth, RGB difference, silhouette) or diff.png")
        ->required();
    cmd->add_option("--min-coverage", args.min_coverage,
                    "Pixels covered less than this are not compared")
        ->capture_default_str();
    cmd->add_option("--color-max", args.color_max_deg,
                    "PNG: degrees at the top of the colour scale")
        ->capture_default_str();
    cmd->callback([] { run(args); });
}

const CommandRegistrar registrar(50, setup);

}  // namespace
}  // namespace glint::cli::compare_command
