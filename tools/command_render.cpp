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
#include "tools/command.h"
#include "tools/progress.h"

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
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

/// "az=30,el=20[,fp=0.1|dist=5]" → a spec (fields not given keep the base values).
ViewSpec parse_view_item(const std::string& item, const ViewSpec& base, const std::string& where) {
    ViewSpec spec = base;
    std::istringstream s(item);
    std::string kv;
    bool has_az = false;
    while (std::getline(s, kv, ',')) {
        const auto eq = kv.find('=');
        if (eq == std::string::npos)
            throw InputError(where + ": \"" + kv + "\", expected key=value");
        const std::string key = kv.substr(0, eq);
        double value = 0.0;
        try {
            std::size_t used = 0;
            value = std::stod(kv.substr(eq + 1), &used);
            if (used != kv.size() - eq - 1) throw std::invalid_argument("trailing");
        } catch (const std::exception&) {
            throw InputError(where + ": \"" + kv + "\", expected a number after '='");
        }
        if (key == "az") {
            spec.azimuth_deg = value;
            has_az = true;
        } else if (key == "el") {
            spec.elevation_deg = value;
        } else if (key == "fp") {
            spec.zoom = ZoomKind::Footprint;
            spec.zoom_value = value;
        } else if (key == "dist") {
            spec.zoom = ZoomKind::Distance;
            spec.zoom_value = value;
        } else {
            throw InputError(where + ": unknown key \"" + key + "\" (az, el, fp, dist)");
        }
    }
    if (!has_az) throw InputError(where + ": \"" + item + "\" has no az=");
    return spec;
}

// note: a views file is a hand-written or generated list of views; 1 MiB holds ~30 000 lines,
// and 10 000 views already take hours. /dev/zero or a FIFO used to grow memory without end.
constexpr std::size_t kMaxViewsFileBytes = std::size_t{1} << 20;
constexpr std::size_t kMaxViews = 10000;

// The views file's text: a regular file (opened without blocking) of at most 1 MiB.
std::string read_views_file(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) throw IoError("cannot read views file \"" + path + "\": " + std::strerror(errno));
    struct stat st {};
    const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    const auto size = static_cast<std::size_t>(regular ? st.st_size : 0);
    std::string text(regular && size <= kMaxViewsFileBytes ? size : 0, '\0');
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::read(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        done += static_cast<std::size_t>(n);
    }
    ::close(fd);
    if (!regular)
        throw InputError("views file \"" + path + "\": not a regular file, expected a text file");
    if (size > kMaxViewsFileBytes)
        throw InputError("views file \"" + path + "\": " + std::to_string(size) +
                         " bytes, expected at most 1 MiB");
    text.resize(done);
    return text;
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
    if (!a.views.empty()) {
        std::istringstream s(a.views);
        std::string item;
        while (std::getline(s, item, ';')) {
            if (!item.empty())
                specs.push_back(parse_view_item(
                    item, base, "--views item " + std::to_string(specs.size() + 1)));
            if (specs.size() > kMaxViews)
                throw InputError("--views: more than " + std::to_string(kMaxViews) +
                                 " views, expected at most " + std::to_string(kMaxViews));
        }
    }
    if (!a.views_file.empty()) {
        std::istringstream in(read_views_file(a.views_file));
        std::string line;
        int line_no = 0;
        while (std::getline(in, line)) {
            ++line_no;
            const auto hash = line.find('#');
            if (hash != std::string::npos) line.erase(hash);
            line.erase(0, line.find_first_not_of(" \t\r"));
            line.erase(line.find_last_not_of(" \t\r") + 1);
            if (line.empty()) continue;
            specs.push_back(
                parse_view_item(line, base, a.views_file + ":" + std::to_string(line_no)));
            if (specs.size() > kMaxViews)
                throw InputError("views file \"" + a.views_file + "\": more than " +
                                 std::to_string(kMaxViews) + " views (line " +
                                 std::to_string(line_no) + "), expected at most " +
                                 std::to_string(kMaxViews));
        }
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
        nlohmann::json report = {{"backend", to_string(info.backend)},
                                 {"device", info.device_name},
                                 {"triangles", info.triangle_count},
                                 {"seconds", seconds},
                                 {"warnings", info.warnings},
                                 {"load_warnings", loaded.report.warnings},
                                 {"frames", written}};
        std::cout << report.dump(2) << '\n';
    } else if (!global_flags().quiet) {
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
