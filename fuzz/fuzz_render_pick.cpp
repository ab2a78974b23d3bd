// libFuzzer harness: the command lines of `glint render` and `glint pick` (issue 23: NaN, Inf
// and 1e30 in --pixel, --footprint, --distance and --distance-px aborted in Embree). The input
// is argv, one token a line ("render", "MESH", "--footprint", "1e30", …); it goes through the
// commands' own flags and checks (tools/view_flags.h), then render's views are placed around
// a sphere and pick's ray is cast into one, so everything short of rendering and writing runs.
// A CLI11 parse error or a glint error is a refusal; anything else is a finding.
#include "fuzz/fuzz_common.h"
#include "mesh/phantom.h"
#include "registration/closest_point.h"
#include "tools/view_flags.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <fstream>
#include <vector>

namespace {

// note: a command line longer than this adds nothing the parser has not seen; the cap keeps
// each execution short.
constexpr std::size_t kMaxTokens = 64;

struct Scene {
    glint::Mesh mesh;
    glint::FramingSphere sphere;
    glint::ClosestPointIndex index;
    std::string views_file;
};

// The mesh every command line is checked against (a small sphere), its picking index, and a
// views file of the harness' own: a path typed in the input would make runs depend on this
// machine's files (views files have their own harness, fuzz_views).
const Scene& scene() {
    static const Scene built = [] {
        glint::Mesh mesh = glint::make_phantom({.resolution = 1});
        const glint::FramingSphere sphere = glint::framing_sphere(mesh);
        glint::ClosestPointIndex index(mesh);
        const auto file = glint::fuzz::write_input(".views.txt", "", nullptr, 0);
        std::ofstream(file) << "az=0,el=0\naz=90,el=30,fp=0.5\n# a comment\naz=180,el=-45\n";
        return Scene{std::move(mesh), sphere, std::move(index), file.string()};
    }();
    return built;
}

std::vector<std::string> tokens(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> out;
    std::string current;
    for (std::size_t i = 0; i < size && out.size() < kMaxTokens; ++i) {
        if (data[i] == '\n') {
            out.push_back(std::move(current));
            current.clear();
        } else {
            current.push_back(static_cast<char>(data[i]));
        }
    }
    if (!current.empty() && out.size() < kMaxTokens) out.push_back(std::move(current));
    return out;
}

void check_command_line(std::vector<std::string> args) {
    const Scene& s = scene();
    CLI::App app("glint");
    glint::cli::RenderArgs render_args;
    glint::cli::PickArgs pick_args;
    auto* render = app.add_subcommand("render");
    glint::cli::add_render_flags(*render, render_args);
    auto* pick = app.add_subcommand("pick");
    glint::cli::add_pick_flags(*pick, pick_args);
    app.require_subcommand(1);
    std::reverse(args.begin(), args.end());  // CLI11 takes them last first
    try {
        app.parse(args);
    } catch (const CLI::Error&) {
        return;  // refused by the parser, as glint's main() would report it
    }
    if (render->parsed()) {
        if (!render_args.views_file.empty()) render_args.views_file = s.views_file;
        glint::cli::RenderRequest request = glint::cli::check_render_args(render_args);
        (void)glint::cli::place_views(s.sphere, request.specs);
    } else if (pick->parsed()) {
        const glint::View view = glint::cli::check_pick_args(s.mesh, pick_args);
        (void)glint::pick(s.index, view.camera, pick_args.pixel[0], pick_args.pixel[1]);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        check_command_line(tokens(data, size));
    } catch (const glint::Error&) {
        // refused with a message: what a hostile command line should get
    }
    return 0;
}
