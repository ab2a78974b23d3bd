// glint pick MESH --azimuth A --elevation E --pixel u,v: which surface point a pixel shows.
#include "analysis/landmarks.h"
#include "mesh/error.h"
#include "mesh/io.h"
#include "registration/closest_point.h"
#include "tools/command.h"

#include <nlohmann/json.hpp>

#include <iostream>
#include <string>
#include <vector>

namespace glint::cli {
namespace {

struct PickArgs {
    std::string mesh;
    double azimuth = 0.0;
    double elevation = 0.0;
    int size = 256;
    double footprint = 0.0;
    std::vector<double> pixel;
};

void run(const PickArgs& a) {
    const LoadedMesh m = load_mesh(a.mesh);
    // note: the framing lives in analysis/landmarks.h so that landmark pixels in
    // `glint register --landmarks` resolve exactly as this command picks them.
    const View view = pick_view(m.mesh, {.azimuth_deg = a.azimuth,
                                         .elevation_deg = a.elevation,
                                         .size = a.size,
                                         .footprint = a.footprint});
    if (a.pixel.size() != 2) throw InputError("--pixel: expected u,v");
    const ClosestPointIndex index(m.mesh);
    const RayHit hit = pick(index, view.camera, a.pixel[0], a.pixel[1]);
    nlohmann::json j = {{"hit", hit.hit}, {"pixel", a.pixel}};
    if (hit.hit) {
        j["point"] = {hit.point.x(), hit.point.y(), hit.point.z()};
        j["triangle"] = hit.triangle;
        j["barycentric"] = {hit.barycentric.x(), hit.barycentric.y(), hit.barycentric.z()};
        j["normal"] = {hit.normal.x(), hit.normal.y(), hit.normal.z()};
        j["distance"] = hit.t;
    }
    if (global_flags().json) std::cout << j.dump(2) << '\n';
    else if (!hit.hit)
        std::cout << "pixel (" << a.pixel[0] << ", " << a.pixel[1] << ") shows no surface\n";
    else
        std::cout << "pixel (" << a.pixel[0] << ", " << a.pixel[1] << ") shows (" << hit.point.x()
                  << ", " << hit.point.y() << ", " << hit.point.z() << ") on triangle "
                  << hit.triangle << " (coordinates in "
                  << (m.mesh.unit.empty() ? std::string("units: the file states none")
                                          : m.mesh.unit)
                  << ")\n";
}

void setup(CLI::App& app) {
    static PickArgs a;
    auto* cmd = app.add_subcommand(
        "pick", "The surface point, triangle and barycentrics under a pixel of a view");
    cmd->add_option("MESH", a.mesh, "Mesh")->required();
    cmd->add_option("--azimuth", a.azimuth, "Degrees")->capture_default_str();
    cmd->add_option("--elevation", a.elevation, "Degrees")->capture_default_str();
    cmd->add_option("--size", a.size, "Image size (framing as glint render)")
        ->capture_default_str();
    cmd->add_option("--footprint", a.footprint, "Mesh units per pixel (default: frame the mesh)");
    cmd->add_option("--pixel", a.pixel, "u,v in pixels (centres at +0.5)")
        ->delimiter(',')
        ->required();
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(45, setup);

}  // namespace
}  // namespace glint::cli
