#include "tools/view_flags.h"

#include "analysis/landmarks.h"
#include "mesh/error.h"
#include "render/context.h"
#include "render/view_list.h"

#include <sstream>
#include <utility>

namespace glint::cli {
namespace {

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

}  // namespace

void add_render_flags(CLI::App& cmd, RenderArgs& args) {
    cmd.add_option("MESH", args.mesh, "Mesh file (PLY, STL, OBJ, OFF, glTF, VTK)")->required();
    cmd.add_option("--azimuth", args.azimuth, "Azimuth, degrees (about +z from +x)")
        ->capture_default_str();
    cmd.add_option("--elevation", args.elevation, "Elevation, degrees (-90..90)")
        ->capture_default_str();
    cmd.add_option("--footprint", args.footprint,
                   "Zoom: mesh units per pixel at the nearest surface");
    cmd.add_option("--distance", args.distance,
                   "Zoom: camera distance from the mesh centre, mesh units");
    cmd.add_option(
        "--distance-px", args.distance_px,
        "Zoom (perspective): distance to the nearest surface in pixels of the fit footprint");
    cmd.add_option("--size", args.size, "Image size W or WxH")->capture_default_str();
    cmd.add_option("--projection", args.projection, "orthographic | perspective")
        ->capture_default_str();
    cmd.add_option("--fov", args.fov_deg, "Perspective vertical field of view, degrees")
        ->capture_default_str();
    cmd.add_option("--mode", args.mode, "normal | reflection | zebra | paper8 | depth")
        ->capture_default_str();
    cmd.add_option("--supersample", args.supersample, "s: s×s sub-samples per pixel (1..8)")
        ->capture_default_str();
    cmd.add_option("--backend", args.backend, "auto | vulkan | embree")->capture_default_str();
    cmd.add_option("--device", args.device,
                   "Vulkan device name (substring); default GLINT_DEVICE or the best");
    cmd.add_option("--normal-space", args.normal_space, "world | view")->capture_default_str();
    cmd.add_option("--min-coverage", args.min_coverage,
                   "Mask pixels covered less than this share (0..1)")
        ->capture_default_str();
    cmd.add_flag("--cull", args.cull, "Cull back faces (closed meshes only)");
    cmd.add_option("--png-bits", args.png_bits, "PNG bit depth: 8 or 16")->capture_default_str();
    cmd.add_option("--views", args.views, "Several views: \"az=0,el=0;az=90,el=30[,fp=F|dist=D]\"");
    cmd.add_option("--views-file", args.views_file,
                   "A file with one view a line: az=…,el=…[,fp=…|dist=…]");
    cmd.add_option("-o,--output", args.output,
                   "Output .exr or .png; with several views {i} is replaced by the view number "
                   "(else _NNN is appended)")
        ->required();
}

RenderRequest check_render_args(const RenderArgs& args) {
    const auto [width, height] = parse_size(args.size);
    RenderRequest request;
    request.specs = view_specs(args, width, height);
    request.shade = ShadeOptions{.mode = parse_shade_mode(args.mode)};
    request.options = render_options(args);
    return request;
}

std::vector<View> place_views(const FramingSphere& sphere, std::vector<ViewSpec>& specs) {
    std::vector<View> views;
    views.reserve(specs.size());
    for (std::size_t i = 0; i < specs.size(); ++i) {
        specs[i].index = static_cast<int>(i);
        views.push_back(make_view(sphere, specs[i]));
    }
    return views;
}

void add_pick_flags(CLI::App& cmd, PickArgs& args) {
    cmd.add_option("MESH", args.mesh, "Mesh")->required();
    cmd.add_option("--azimuth", args.azimuth, "Degrees")->capture_default_str();
    cmd.add_option("--elevation", args.elevation, "Degrees")->capture_default_str();
    cmd.add_option("--size", args.size, "Image size (framing as glint render)")
        ->capture_default_str();
    cmd.add_option("--footprint", args.footprint, "Mesh units per pixel (default: frame the mesh)");
    cmd.add_option("--pixel", args.pixel, "u,v in pixels (centres at +0.5)")
        ->delimiter(',')
        ->required();
}

View check_pick_args(const Mesh& mesh, const PickArgs& args) {
    // note: the framing lives in analysis/landmarks.h so that landmark pixels in
    // `glint register --landmarks` resolve exactly as this command picks them.
    const View view = pick_view(mesh, {.azimuth_deg = args.azimuth,
                                       .elevation_deg = args.elevation,
                                       .size = args.size,
                                       .footprint = args.footprint});
    if (args.pixel.size() != 2) throw InputError("--pixel: expected u,v");
    return view;
}

}  // namespace glint::cli
