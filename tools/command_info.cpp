// glint info MESH…: what a mesh file holds, what loading repaired, what validation found.
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/json_text.h"
#include "mesh/units.h"
#include "mesh/validate.h"
#include "mesh/voxel_grid.h"
#include "tools/command.h"
#include "tools/surface_flags.h"
#include "volume/surface.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace glint::cli::info_command {
namespace {

// The CT grid a segmentation export was extracted on, read back from its vertices
// (mesh/voxel_grid.h): what sweep reads thin plates and gaps against; null when none is read.
nlohmann::json grid_json(const Mesh& mesh) {
    const auto g = detect_voxel_grid(mesh);
    if (!g) return nullptr;
    return {{"spacing", {g->spacing.x(), g->spacing.y(), g->spacing.z()}},
            {"read_from", g->smoothed ? "period" : "edges"},
            {"periodicity", g->smoothed ? nlohmann::json(g->periodicity) : nlohmann::json()}};
}

nlohmann::json to_json(const LoadedMesh& loaded, const ValidationReport& v) {
    const auto& r = loaded.report;
    const Vec3f extent = v.bounds.extent();
    std::vector<std::string> scalar_names;
    for (const auto& s : loaded.mesh.scalars) scalar_names.push_back(s.name);
    return {
        {"path", r.path.string()},
        {"format", r.format},
        {"unit", loaded.mesh.unit},
        {"vertices", v.vertices},
        {"triangles", v.triangles},
        {"bounds",
         {{"min", {v.bounds.min.x(), v.bounds.min.y(), v.bounds.min.z()}},
          {"max", {v.bounds.max.x(), v.bounds.max.y(), v.bounds.max.z()}},
          {"extent", {extent.x(), extent.y(), extent.z()}}}},
        {"area", v.area},
        {"closed", v.is_closed},
        {"boundary_edges", v.boundary_edges},
        {"non_manifold_edges", v.non_manifold_edges},
        {"components", v.components},
        {"scalars", scalar_names},
        {"has_labels", !loaded.mesh.labels.empty()},
        {"has_colors", !loaded.mesh.colors.empty()},
        {"repairs",
         {{"file_vertices", r.file_vertices},
          {"file_triangles", r.file_triangles},
          {"welded_vertices", r.welded_vertices},
          {"importer_corner_vertices", r.importer_corner_vertices},
          {"degenerate_triangles", r.degenerate_triangles},
          {"duplicate_triangles", r.duplicate_triangles},
          {"unused_vertices", r.unused_vertices},
          {"split_polygons", r.split_polygons}}},
        {"findings", v.findings},
        {"warnings", r.warnings},
        {"grid", grid_json(loaded.mesh)},
    };
}

void print_text(const nlohmann::json& j) {
    auto num = [](const nlohmann::json& x) { return json_text(x); };
    const std::string unit = j["unit"].get<std::string>();
    std::cout << terminal_safe(j["path"].get<std::string>()) << '\n'
              << "  format      " << j["format"].get<std::string>() << ", unit "
              << (unit.empty() ? "unknown (the file states none; give --unit to sweep/register/run)"
                               : unit)
              << '\n'
              << "  vertices    " << num(j["vertices"]) << "   triangles " << num(j["triangles"])
              << '\n';
    const auto& e = j["bounds"]["extent"];
    char line[160];
    std::snprintf(line, sizeof line, "  extent      %.4g x %.4g x %s   area %s\n",
                  e[0].get<double>(), e[1].get<double>(),
                  with_unit(e[2].get<double>(), unit).c_str(),
                  with_unit(j["area"].get<double>(), unit, 2, "%.6g").c_str());
    std::cout << line;
    std::cout << "  topology    " << (j["closed"].get<bool>() ? "closed" : "open") << ", "
              << num(j["components"]) << " component(s), " << num(j["boundary_edges"])
              << " boundary / " << num(j["non_manifold_edges"]) << " non-manifold edges\n";
    const auto& r = j["repairs"];
    if (r["importer_corner_vertices"].get<std::size_t>() > 0)
        std::cout << "  OBJ         the importer made one vertex per face corner ("
                  << num(r["importer_corner_vertices"]) << "), merged back to the file's "
                  << num(r["file_vertices"]) << " vertices (v lines)\n";
    std::cout << "  repairs     welded " << num(r["welded_vertices"]) << " vertices, dropped "
              << num(r["degenerate_triangles"]) << " degenerate + " << num(r["duplicate_triangles"])
              << " duplicate triangles and " << num(r["unused_vertices"])
              << " unused vertices, split " << num(r["split_polygons"]) << " polygons\n";
    if (!j["scalars"].empty()) std::cout << "  scalars     " << json_text(j["scalars"]) << '\n';
    if (const auto& g = j["grid"]; !g.is_null()) {
        const auto& s = g["spacing"];
        std::snprintf(line, sizeof line, "  grid        %.4g x %.4g x %s, ", s[0].get<double>(),
                      s[1].get<double>(), with_unit(s[2].get<double>(), unit).c_str());
        std::cout << line
                  << (g["read_from"] == "edges"
                          ? "marching-cubes output (its vertices lie on the grid's edges)"
                          : "a smoothed marching-cubes export (its vertices crowd near the "
                            "grid's planes)")
                  << ": sweep compares no thin plate or gap below it\n";
    }
    for (const auto& f : j["findings"])
        std::cout << "  finding     " << terminal_safe(f.get<std::string>()) << '\n';
    for (const auto& w : j["warnings"])
        std::cout << "  warning     " << terminal_safe(w.get<std::string>()) << '\n';
}

nlohmann::json volume_json(const Volume& v) {
    const VolumeGeometry& g = v.geometry;
    const auto range = v.range();
    nlohmann::json direction = nlohmann::json::array();
    for (int r = 0; r < 3; ++r)
        direction.push_back({g.direction(r, 0), g.direction(r, 1), g.direction(r, 2)});
    const Vec3d far = g.physical_from_index(
        Vec3d(double(g.size[0] - 1), double(g.size[1] - 1), double(g.size[2] - 1)));
    return {{"path", v.path.string()},
            {"format", v.format},
            {"stored_type", v.stored_type},
            {"size", g.size},
            {"spacing_mm", {g.spacing.x(), g.spacing.y(), g.spacing.z()}},
            {"origin_mm", {g.origin.x(), g.origin.y(), g.origin.z()}},
            {"direction", direction},
            {"last_voxel_mm", {far.x(), far.y(), far.z()}},
            {"range", {range[0], range[1]}}};
}

void print_volume(const nlohmann::json& j) {
    const auto& d = j["direction"];
    std::printf(
        "%s\n  format      %s volume, %s voxels\n  size        %zu x %zu x %zu\n"
        "  spacing     %.6g x %.6g x %.6g mm\n  origin      (%.6g, %.6g, %.6g) mm\n"
        "  direction   [%.4g %.4g %.4g; %.4g %.4g %.4g; %.4g %.4g %.4g]\n  range       %.6g … %.6g\n",
        terminal_safe(j["path"].get<std::string>()).c_str(), j["format"].get<std::string>().c_str(),
        j["stored_type"].get<std::string>().c_str(), j["size"][0].get<std::size_t>(),
        j["size"][1].get<std::size_t>(), j["size"][2].get<std::size_t>(),
        j["spacing_mm"][0].get<double>(), j["spacing_mm"][1].get<double>(),
        j["spacing_mm"][2].get<double>(), j["origin_mm"][0].get<double>(),
        j["origin_mm"][1].get<double>(), j["origin_mm"][2].get<double>(), d[0][0].get<double>(),
        d[0][1].get<double>(), d[0][2].get<double>(), d[1][0].get<double>(), d[1][1].get<double>(),
        d[1][2].get<double>(), d[2][0].get<double>(), d[2][1].get<double>(), d[2][2].get<double>(),
        j["range"][0].get<double>(), j["range"][1].get<double>());
}

// A volume: its geometry and range; with --iso also the surface, as for a mesh.
nlohmann::json volume_info(const std::string& path, const SurfaceOptions& surface) {
    const Volume volume = read_volume(path);
    nlohmann::json j = volume_json(volume);
    if (!global_flags().json) print_volume(j);
    if (!surface.iso) {
        if (!global_flags().json) std::printf("  surface     give --iso VALUE to extract one\n");
        return j;
    }
    ExtractedSurface s = extract_surface(volume, surface);
    LoadedMesh loaded{std::move(s.mesh), {}};
    loaded.report.path = path;
    loaded.report.format = "surface at iso";
    const ValidationReport v = validate_mesh(loaded.mesh, path);
    j["surface"] = to_json(loaded, v);
    if (!global_flags().json) {
        std::printf("  surface     %s\n", describe(s.report).c_str());
        print_text(j["surface"]);
    }
    return j;
}

void setup(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "info",
        "Counts, bounds, unit, repairs and validation findings of mesh files; geometry and range of volumes");
    static std::vector<std::string> paths;
    static SurfaceOptions surface;
    cmd->add_option(
           "MESH", paths,
           "Mesh files (PLY, STL, OBJ, OFF, glTF/GLB, VTK legacy) or volumes (.mhd .mha .nii .nii.gz .nrrd "
           ".nhdr, a DICOM folder)")
        ->required();
    add_surface_flags(*cmd, surface);
    cmd->callback([] {
        nlohmann::json all = nlohmann::json::array();
        for (const auto& path : paths) {
            if (is_volume_path(path)) {
                all.push_back(volume_info(path, surface));
                continue;
            }
            if (surface.iso || surface.any())
                throw InputError(
                    "mesh \"" + path +
                    "\": surface options (--iso, …) apply to volumes, this is a mesh file");
            const LoadedMesh loaded = load_mesh(path);
            const ValidationReport v = validate_mesh(loaded.mesh, path);
            all.push_back(to_json(loaded, v));
            if (!global_flags().json) print_text(all.back());
        }
        if (global_flags().json) std::cout << json_text(all, 2) << '\n';
    });
}

const CommandRegistrar registrar(10, setup);

}  // namespace
}  // namespace glint::cli::info_command
