// glint surface VOLUME --iso VALUE [-o mesh.ply] …: the bone surface of a CT (or any
// iso-surface of a volume) in physical coordinates (mm), with a report of what was done.
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/write.h"
#include "tools/command.h"
#include "tools/surface_flags.h"
#include "volume/surface.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <string>

namespace glint::cli::surface_command {
namespace {

struct SurfaceArgs {
    std::string volume;
    SurfaceOptions options;
    std::string output;
};

nlohmann::json to_json(const SurfaceReport& r, const std::string& volume,
                       const std::string& output) {
    return {{"volume", volume},
            {"output", absolute_output(output)},
            {"voxels", r.voxels},
            {"cropped_voxels", r.cropped},
            {"spacing_mm", {r.spacing.x(), r.spacing.y(), r.spacing.z()}},
            {"iso", r.iso},
            {"range", {r.range[0], r.range[1]}},
            {"components_found", r.components_found},
            {"components_kept", r.components_kept},
            {"contour_triangles", r.contour_triangles},
            {"triangles", r.triangles},
            {"vertices", r.vertices},
            {"decimation_error_mm", r.decimation_error_mm},
            {"seconds", r.seconds},
            {"notes", r.notes}};
}

void run(const SurfaceArgs& a) {
    if (!a.options.iso) a.options.validate();  // names the missing iso before reading anything
    guard_outputs({a.output}, {a.volume});
    const Volume volume = read_volume(a.volume);
    const ExtractedSurface s = extract_surface(volume, a.options);
    if (!a.output.empty()) write_mesh(s.mesh, a.output);
    if (global_flags().json) {
        std::cout << json_text(to_json(s.report, a.volume, a.output), 2) << '\n';
        return;
    }
    std::printf("%s\n", describe(s.report).c_str());
    for (const auto& note : s.report.notes) std::printf("  %s\n", note.c_str());
    if (!a.output.empty()) std::printf("wrote %s (mm)\n", a.output.c_str());
}

void setup(CLI::App& app) {
    static SurfaceArgs a;
    auto* cmd = app.add_subcommand(
        "surface", "Extract an iso-surface (e.g. bone) from a CT volume, in physical mm");
    cmd->add_option("VOLUME", a.volume,
                    "Volume: .mhd/.raw, .mha, .nii, .nii.gz, .nrrd, .nhdr or a DICOM series folder")
        ->required();
    add_surface_flags(*cmd, a.options, "--roi");
    cmd->add_option("-o,--output", a.output,
                    "Surface mesh to write (.ply, .vtk, .vtp, .stl, .obj, .off)");
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(15, setup);

}  // namespace
}  // namespace glint::cli::surface_command
