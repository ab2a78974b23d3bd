// glint pick MESH --azimuth A --elevation E --pixel u,v: which surface point a pixel shows.
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/json_text.h"
#include "registration/closest_point.h"
#include "tools/command.h"
#include "tools/view_flags.h"

#include <nlohmann/json.hpp>

#include <iostream>
#include <string>
#include <vector>

namespace glint::cli::pick_command {
namespace {

void run(const PickArgs& a) {
    const LoadedMesh m = load_mesh(a.mesh);
    const View view = check_pick_args(m.mesh, a);
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
    if (global_flags().json) std::cout << json_text(j, 2) << '\n';
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
    add_pick_flags(*cmd, a);
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(45, setup);

}  // namespace
}  // namespace glint::cli::pick_command
