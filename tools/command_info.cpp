// glint info MESH…: what a mesh file holds, what loading repaired, what validation found.
#include "mesh/io.h"
#include "mesh/units.h"
#include "mesh/validate.h"
#include "tools/command.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace glint::cli {
namespace {

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
        {"bounds", {{"min", {v.bounds.min.x(), v.bounds.min.y(), v.bounds.min.z()}},
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
        {"repairs", {{"file_vertices", r.file_vertices},
                     {"file_triangles", r.file_triangles},
                     {"welded_vertices", r.welded_vertices},
                     {"importer_corner_vertices", r.importer_corner_vertices},
                     {"degenerate_triangles", r.degenerate_triangles},
                     {"duplicate_triangles", r.duplicate_triangles},
                     {"unused_vertices", r.unused_vertices},
                     {"split_polygons", r.split_polygons}}},
        {"findings", v.findings},
        {"warnings", r.warnings},
    };
}

void print_text(const nlohmann::json& j) {
    auto num = [](const nlohmann::json& x) { return x.dump(); };
    const std::string unit = j["unit"].get<std::string>();
    std::cout << j["path"].get<std::string>() << '\n'
              << "  format      " << j["format"].get<std::string>() << ", unit "
              << (unit.empty() ? "unknown (the file states none; give --unit to sweep/register/run)" : unit) << '\n'
              << "  vertices    " << num(j["vertices"]) << "   triangles " << num(j["triangles"]) << '\n';
    const auto& e = j["bounds"]["extent"];
    char line[160];
    std::snprintf(line, sizeof line, "  extent      %.4g x %.4g x %s   area %s\n", e[0].get<double>(),
                  e[1].get<double>(), with_unit(e[2].get<double>(), unit).c_str(),
                  with_unit(j["area"].get<double>(), unit, 2, "%.6g").c_str());
    std::cout << line;
    std::cout << "  topology    " << (j["closed"].get<bool>() ? "closed" : "open") << ", "
              << num(j["components"]) << " component(s), " << num(j["boundary_edges"])
              << " boundary / " << num(j["non_manifold_edges"]) << " non-manifold edges\n";
    const auto& r = j["repairs"];
    if (r["importer_corner_vertices"].get<std::size_t>() > 0)
        std::cout << "  OBJ         the importer made one vertex per face corner ("
                  << num(r["importer_corner_vertices"]) << "), merged back to the file's " << num(r["file_vertices"])
                  << " vertices (v lines)\n";
    std::cout << "  repairs     welded " << num(r["welded_vertices"]) << " vertices, dropped "
              << num(r["degenerate_triangles"]) << " degenerate + " << num(r["duplicate_triangles"])
              << " duplicate triangles and " << num(r["unused_vertices"]) << " unused vertices, split "
              << num(r["split_polygons"]) << " polygons\n";
    if (!j["scalars"].empty()) std::cout << "  scalars     " << j["scalars"].dump() << '\n';
    for (const auto& f : j["findings"]) std::cout << "  finding     " << f.get<std::string>() << '\n';
    for (const auto& w : j["warnings"]) std::cout << "  warning     " << w.get<std::string>() << '\n';
}

void setup(CLI::App& app) {
    auto* cmd = app.add_subcommand("info", "Counts, bounds, unit, repairs and validation findings of mesh files");
    static std::vector<std::string> paths;
    cmd->add_option("MESH", paths, "Mesh files (PLY, STL, OBJ, OFF, glTF/GLB, VTK legacy)")->required();
    cmd->callback([] {
        nlohmann::json all = nlohmann::json::array();
        for (const auto& path : paths) {
            const LoadedMesh loaded = load_mesh(path);
            const ValidationReport v = validate_mesh(loaded.mesh, path);
            all.push_back(to_json(loaded, v));
            if (!global_flags().json) print_text(all.back());
        }
        if (global_flags().json) std::cout << all.dump(2) << '\n';
    });
}

const CommandRegistrar registrar(10, setup);

}  // namespace
}  // namespace glint::cli
