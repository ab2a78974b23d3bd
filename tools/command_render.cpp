// glint render MESH …: renders one or several views of a mesh into EXR (numbers) or PNG
// (for eyes) images, with the view in the image metadata.
//
//   glint render jaw.obj --azimuth 30 --elevation 20 --footprint 0.1 --size 512 -o jaw.png
//   glint render jaw.obj --views "az=0,el=0;az=90,el=30" --mode reflection -o jaw_{i}.exr
//   glint render jaw.obj --views-file views.txt -o out/{i}.exr     (one "az=…,el=…" a line)
#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/output_guard.h"
#include "render/image_io.h"
#include "render/renderer.h"
#include "render/shade.h"
#include "render/view.h"
#include "render/view_list.h"
#include "tools/command.h"
#include "tools/progress.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace glint::cli {
namespace {

struct RenderArgs {
    std::string mesh;
    double azimuth = 0.0;
    double elevation = 0.0;
    std::optional<double> footprint;
    std::optional<double> distance;
    std::optional<double> distance_px;
    std::string size = "512";
    std::string projection = "orthographic";
    double fov_deg = 30.0;
    std::string mode = "normal";
    int supersample = 2;
    std::string backend = "auto";
    std::string device;
    std::string normal_space = "world";
    float min_coverage = 0.0f;
    bool cull = false;
    int png_bits = 8;
    std::string views;
    std::string views_file;
    std::string output;
};

std::pair<int, int> parse_size(const std::string& text) {
    int w = 0, h = 0;
    char x = 0;
    std::istringstream s(text);
    if (!(s >> w)) throw InputError("--size \"" + text + "\": expected W or WxH");
    if (s >> x) {
        if ((x != 'x' && x != 'X') || !(s >> h))
            throw InputError("--size \"" + text + "\": expected W or WxH");
    } else {
        h = w;
    }
    std::string rest;
    if (s >> rest) throw InputError("--size \"" + text + "\": unexpected \"" + rest + "\"");
    return {w, h};
}

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

// The base view the flags describe (azimuth, elevation, size, projection, one zoom).
ViewSpec base_view(const RenderArgs& a, int width, int height) {
    ViewSpec base;
    base.azimuth_deg = a.azimuth;
    base.elevation_deg = a.elevation;
    base.width = width;
    base.height = height;
    base.projection = parse_projection(a.projection);
    base.fov_y_rad = a.fov_deg * 3.14159265358979323846 / 180.0;
    const int zooms = (a.footprint ? 1 : 0) + (a.distance ? 1 : 0) + (a.distance_px ? 1 : 0);
    if (zooms > 1) throw InputError("give at most one of --footprint, --distance, --distance-px");
    if (a.footprint) {
        base.zoom = ZoomKind::Footprint;
        base.zoom_value = *a.footprint;
    } else if (a.distance) {
        base.zoom = ZoomKind::Distance;
        base.zoom_value = *a.distance;
    } else if (a.distance_px) {
        base.zoom = ZoomKind::DistancePixels;
        base.zoom_value = *a.distance_px;
    }
    return base;
}

// The views to render: --views items and views-file lines over the base view, or the base view.
std::vector<ViewSpec> view_specs(const RenderArgs& a, int width, int height) {
    const ViewSpec base = base_view(a, width, height);
    std::vector<ViewSpec> specs;
    if (!a.views.empty()) specs = parse_view_list(a.views, ';', base, "--views");
    if (!a.views_file.empty()) {
        auto listed = parse_view_list(read_views_file(a.views_file), '\n', base,
                                      "views file \"" + a.views_file + "\"");
        if (specs.size() + listed.size() > kMaxListedViews)
            throw InputError(
                "--views and --views-file: " + std::to_string(specs.size() + listed.size()) +
                " views together, expected at most " + std::to_string(kMaxListedViews));
        specs.insert(specs.end(), listed.begin(), listed.end());
    }
    if (specs.empty()) specs.push_back(base);
    return specs;
}

RenderOptions render_options(const RenderArgs& a) {
    RenderOptions options;
    options.backend = parse_backend(a.backend);
    options.device = a.device;
    options.supersample = a.supersample;
    options.min_coverage = a.min_coverage;
    options.cull_back_faces = a.cull;
    if (a.normal_space == "world") {
        options.normal_space = NormalSpace::World;
    } else if (a.normal_space == "view") {
        options.normal_space = NormalSpace::View;
    } else {
        throw InputError("--normal-space \"" + a.normal_space + "\": expected world or view");
    }
    options.validate();
    return options;
}

void run(const RenderArgs& a) {
    guard_outputs({a.output}, {a.mesh, a.views_file});
    const auto [width, height] = parse_size(a.size);
    std::vector<ViewSpec> specs = view_specs(a, width, height);

    const ShadeOptions shade{.mode = parse_shade_mode(a.mode)};
    const RenderOptions options = render_options(a);

    const LoadedMesh loaded = load_mesh(a.mesh);
    const FramingSphere sphere = framing_sphere(loaded.mesh);
    std::vector<View> views;
    for (std::size_t i = 0; i < specs.size(); ++i) {
        specs[i].index = static_cast<int>(i);
        views.push_back(make_view(sphere, specs[i]));
    }
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
        std::cout << report.dump(2) << '\n';
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
    cmd->add_option("MESH", args.mesh, "Mesh file (PLY, STL, OBJ, OFF, glTF, VTK)")->required();
    cmd->add_option("--azimuth", args.azimuth, "Azimuth, degrees (about +z from +x)")
        ->capture_default_str();
    cmd->add_option("--elevation", args.elevation, "Elevation, degrees (-90..90)")
        ->capture_default_str();
    cmd->add_option("--footprint", args.footprint,
                    "Zoom: mesh units per pixel at the nearest surface");
    cmd->add_option("--distance", args.distance,
                    "Zoom: camera distance from the mesh centre, mesh units");
    cmd->add_option(
        "--distance-px", args.distance_px,
        "Zoom (perspective): distance to the nearest surface in pixels of the fit footprint");
    cmd->add_option("--size", args.size, "Image size W or WxH")->capture_default_str();
    cmd->add_option("--projection", args.projection, "orthographic | perspective")
        ->capture_default_str();
    cmd->add_option("--fov", args.fov_deg, "Perspective vertical field of view, degrees")
        ->capture_default_str();
    cmd->add_option("--mode", args.mode, "normal | reflection | zebra | paper8 | depth")
        ->capture_default_str();
    cmd->add_option("--supersample", args.supersample, "s: s×s sub-samples per pixel (1..8)")
        ->capture_default_str();
    cmd->add_option("--backend", args.backend, "auto | vulkan | embree")->capture_default_str();
    cmd->add_option("--device", args.device,
                    "Vulkan device name (substring); default GLINT_DEVICE or the best");
    cmd->add_option("--normal-space", args.normal_space, "world | view")->capture_default_str();
    cmd->add_option("--min-coverage", args.min_coverage,
                    "Mask pixels covered less than this share (0..1)")
        ->capture_default_str();
    cmd->add_flag("--cull", args.cull, "Cull back faces (closed meshes only)");
    cmd->add_option("--png-bits", args.png_bits, "PNG bit depth: 8 or 16")->capture_default_str();
    cmd->add_option("--views", args.views,
                    "Several views: \"az=0,el=0;az=90,el=30[,fp=F|dist=D]\"");
    cmd->add_option("--views-file", args.views_file,
                    "A file with one view a line: az=…,el=…[,fp=…|dist=…]");
    cmd->add_option("-o,--output", args.output,
                    "Output .exr or .png; with several views {i} is replaced by the view number "
                    "(else _NNN is appended)")
        ->required();
    cmd->callback([] { run(args); });
}

const CommandRegistrar registrar(40, setup);

}  // namespace
}  // namespace glint::cli
