// The command lines of `glint render` and `glint pick` up to their work: the flags, bound to
// plain structs, and the checks of what they ask for (size, views, zoom, modes, pixel). Kept
// apart from the commands so that fuzz/fuzz_view_flags.cpp parses and checks hostile command
// lines with the very same code (issue 23: NaN, Inf or 1e30 in --pixel, --footprint,
// --distance and --distance-px aborted in Embree). Nothing here loads, renders or writes.
#pragma once

#include "mesh/mesh.h"
#include "render/renderer.h"
#include "render/shade.h"
#include "render/view.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace glint::cli {

/// What `glint render` was asked for, as typed.
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

/// Adds render's positional MESH and flags to `command`, bound to `args` (which must outlive it).
void add_render_flags(CLI::App& command, RenderArgs& args);

/// A render request checked before the mesh is loaded: every view spec (validated), the
/// shading and the renderer's options.
struct RenderRequest {
    std::vector<ViewSpec> specs;
    ShadeOptions shade;
    RenderOptions options;
};

/// Checks `args` and reads the views file when one is given. \throw InputError naming the flag
/// and the value; IoError for an unreadable views file.
[[nodiscard]] RenderRequest check_render_args(const RenderArgs& args);

/// The request's views around `sphere`, numbered in order. \throw InputError for a view the
/// framing makes implausible (e.g. a distance inside the mesh, a footprint of 1e30).
[[nodiscard]] std::vector<View> place_views(const FramingSphere& sphere,
                                            std::vector<ViewSpec>& specs);

/// What `glint pick` was asked for, as typed.
struct PickArgs {
    std::string mesh;
    double azimuth = 0.0;
    double elevation = 0.0;
    int size = 256;
    double footprint = 0.0;
    std::vector<double> pixel;
};

/// Adds pick's positional MESH and flags to `command`, bound to `args`.
void add_pick_flags(CLI::App& command, PickArgs& args);

/// The view `args` names around `mesh` (framed as analysis/landmarks.h's pick_view), with
/// --pixel checked to be two numbers; pick() then checks that the pixel lies in the view, so
/// that only finite, in-image rays reach Embree. \throw InputError naming the flag and value.
[[nodiscard]] View check_pick_args(const Mesh& mesh, const PickArgs& args);

}  // namespace glint::cli
