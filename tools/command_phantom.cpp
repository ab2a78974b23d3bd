// glint phantom KIND …: a procedural surface, optionally damaged and posed, with its ground
// truth (labels and displacement as PLY/VTK scalars, and a JSON sidecar with every parameter).
#include "mesh/atomic_file.h"
#include "mesh/damage.h"
#include "mesh/error.h"
#include "mesh/file_set.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/phantom.h"
#include "mesh/validate.h"
#include "mesh/write.h"
#include "tools/command.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace glint::cli::phantom_command {
namespace {

struct PhantomArgs {
    std::string kind;
    int resolution = 5;
    std::string scheme = "ico";
    std::vector<double> size;
    std::vector<std::string> damages;
    std::string pose;
    std::string output;
};

nlohmann::json rigid_json(const Rigid& t) {
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({t(r, 0), t(r, 1), t(r, 2), t(r, 3)});
    return rows;
}

void run(const PhantomArgs& a) {
    const std::string sidecar_path = a.output + ".json";
    guard_outputs({a.output, sidecar_path}, {});
    PhantomOptions options;
    options.kind = parse_phantom_kind(a.kind);
    options.scheme = parse_scheme(a.scheme);
    options.resolution = a.resolution;
    if (!a.size.empty()) {
        // A torus has two sizes, as the help says (issue 52: "--size 20 5" was refused).
        const bool torus = options.kind == PhantomKind::Torus;
        if (a.size.size() == 1) options.radii = Vec3d::Constant(a.size[0]);
        else if (torus && a.size.size() == 2) options.radii = {a.size[0], a.size[1], a.size[1]};
        else if (!torus && a.size.size() == 3) options.radii = {a.size[0], a.size[1], a.size[2]};
        else
            throw InputError("--size: expected " +
                             std::string(torus ? "1 or 2 numbers (major, minor radius)"
                                               : "1 or 3 numbers (radius, or three semi-axes)") +
                             ", found " + std::to_string(a.size.size()));
    }
    Mesh mesh = make_phantom(options);
    std::vector<DamageSpec> specs;
    for (const auto& text : a.damages) specs.push_back(parse_damage_spec(text));
    if (!specs.empty()) apply_damage(mesh, specs);
    Rigid pose = Rigid::Identity();
    if (!a.pose.empty()) {
        pose = parse_pose_spec(a.pose);
        transform_mesh(mesh, pose);
    }
    FileSet files;  // the mesh and its sidecar appear together or not at all
    files.add(a.output, [&](const std::filesystem::path& temp) { write_mesh(mesh, temp); });

    const ValidationReport v = validate_mesh(mesh, a.output);
    std::size_t damaged = 0;
    for (auto l : mesh.labels) damaged += l != 0;
    nlohmann::json sidecar = {
        {"kind", to_string(options.kind)},
        {"scheme", to_string(options.scheme)},
        {"resolution", options.resolution},
        {"radii", {options.radii.x(), options.radii.y(), options.radii.z()}},
        {"unit", mesh.unit},
        {"damages", a.damages},
        {"pose", a.pose},
        {"world_from_phantom", rigid_json(pose)},
        {"vertices", v.vertices},
        {"triangles", v.triangles},
        {"damaged_vertices", damaged},
        {"mesh", std::filesystem::path(a.output).filename().string()},
    };
    files.add(sidecar_path, json_text(sidecar, 2) + "\n");
    files.commit();
    if (global_flags().json) {
        // The sidecar's content and where both files are (the sidecar names the mesh only by
        // its file name: the pair may be moved together).
        nlohmann::json printed = sidecar;
        printed["output"] = absolute_output(a.output);
        printed["sidecar"] = absolute_output(sidecar_path);
        std::cout << json_text(printed, 2) << '\n';
    } else {
        std::cout << "wrote " << a.output << " (" << v.vertices << " vertices, " << v.triangles
                  << " triangles, " << damaged << " damaged vertices) and " << sidecar_path << '\n';
    }
}

void setup(CLI::App& app) {
    static PhantomArgs args;
    auto* cmd = app.add_subcommand("phantom",
                                   "Write a procedural surface (sphere, ellipsoid, torus, condyle) "
                                   "with optional damage and pose, and its ground truth");
    cmd->add_option("KIND", args.kind, "sphere | ellipsoid | torus | condyle")->required();
    cmd->add_option("--resolution", args.resolution, "uv: latitude rings; ico: subdivision level")
        ->capture_default_str();
    cmd->add_option("--scheme", args.scheme, "Tessellation: uv | ico")->capture_default_str();
    cmd->add_option("--size", args.size,
                    "Radius, or three semi-axes (torus: major minor); mesh units (mm)")
        ->expected(1, 3);
    cmd->add_option(
        "--damage", args.damages,
        "Damage spec, repeatable (docs/commands.md: dent:center=x,y,z;radius=R;depth=D)");
    cmd->add_option("--pose", args.pose, "Rigid pose 'rx,ry,rz,tx,ty,tz' (degrees, mesh units)");
    cmd->add_option(
           "-o,--output", args.output,
           "Output mesh (.ply, .vtk, .vtp, .stl, .obj, .off); a .json sidecar is written beside it")
        ->required();
    cmd->callback([] { run(args); });
}

const CommandRegistrar registrar(20, setup);

}  // namespace
}  // namespace glint::cli::phantom_command
