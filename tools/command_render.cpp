// glint render MESH …: renders one or several views of a mesh into EXR (numbers) or PNG
// (for eyes) images, with the view in the image metadata.
//
//   glint render jaw.obj --azimuth 30 --elevation 20 --footprint 0.1 --size 512 -o jaw.png
//   glint render jaw.obj --views "az=0,el=0;az=90,el=30" --mode reflection -o jaw_{i}.exr
//   glint render jaw.obj --views-file views.txt -o out/{i}.exr     (one "az=…,el=…" a line)
#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "render/image_io.h"
#include "render/renderer.h"
#include "render/shade.h"
#include "render/view.h"
#include "tools/command.h"
#include "tools/progress.h"
#include "tools/view_flags.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <iostream>
#include <string>
#include <vector>

namespace glint::cli::render_command {
namespace {

std::string output_for(const std::string& pattern, std::size_t index, std::size_t count) {
    if (count == 1 && pattern.find("{i}") == std::string::npos) return pattern;
    char num[16];
    std::snprintf(num, sizeof num, "%03zu", index);
    std::string out = pattern;
    const auto pos = out.find("{i}");
    if (pos != std::string::npos) return out.replace(pos, 3, num);
    const std::filesystem::path p(pattern);
    return (p.parent_path() / (p.stem().string() + "_" + num + p.extension().string())).string();
}

void run(const RenderArgs& a) {
    guard_outputs({a.output}, {a.mesh, a.views_file});
    RenderRequest request = check_render_args(a);
    const ShadeOptions& shade = request.shade;
    const RenderOptions& options = request.options;

    const LoadedMesh loaded = load_mesh(a.mesh);
    const std::vector<View> views = place_views(framing_sphere(loaded.mesh), request.specs);
    const auto t0 = std::chrono::steady_clock::now();
    Renderer renderer(loaded.mesh, options);
    const RendererInfo& info = renderer.info();
    FrameImageOptions image_options{.shade = shade, .png_bits = a.png_bits};
    image_options.metadata["device"] = info.device_name;
    image_options.metadata["backend"] = to_string(info.backend);
    image_options.metadata["mesh"] = std::filesystem::path(a.mesh).filename().string();
    image_options.metadata["supersample"] = std::to_string(options.supersample);
    nlohmann::json written = nlohmann::json::array();
    ProgressBar progress("render", views.size());
    renderer.render_views(views, [&](std::size_t i, const Frame& frame) {
        const std::string path = output_for(a.output, i, views.size());
        write_frame_image(path, frame, views[i], image_options);
        written.push_back({{"path", path},
                           {"azimuth_deg", views[i].azimuth_deg},
                           {"elevation_deg", views[i].elevation_deg},
                           {"footprint", views[i].footprint},
                           {"covered_pixels", frame.covered_count()}});
        progress.update(i + 1);
    });
    progress.finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (global_flags().json) {
        nlohmann::json report = {{"output", absolute_output(a.output)},
                                 {"backend", to_string(info.backend)},
                                 {"device", info.device_name},
                                 {"triangles", info.triangle_count},
                                 {"seconds", seconds},
                                 {"warnings", info.warnings},
                                 {"load_warnings", loaded.report.warnings},
                                 {"frames", written}};
        std::cout << json_text(report, 2) << '\n';
    } else {
        if (!global_flags().quiet)
            for (const auto& w : info.warnings) std::cerr << "glint: note: " << w << '\n';
        for (const auto& f : written) {
            std::cout << "wrote " << f["path"].get<std::string>() << " (az "
                      << f["azimuth_deg"].get<double>() << "°, el "
                      << f["elevation_deg"].get<double>() << "°, footprint "
                      << f["footprint"].get<double>() << ", "
                      << f["covered_pixels"].get<std::size_t>() << " px covered)\n";
        }
        std::cout << views.size() << " view(s) in " << seconds << " s on " << info.device_name
                  << " (" << to_string(info.backend) << ")\n";
    }
}

void setup(CLI::App& app) {
    static RenderArgs args;
    auto* cmd = app.add_subcommand(
        "render", "Render normal-colour frames of a mesh (EXR numbers, PNG for eyes)");
    add_render_flags(*cmd, args);
    cmd->callback([] { run(args); });
}

const CommandRegistrar registrar(40, setup);

}  // namespace
}  // namespace glint::cli::render_command
