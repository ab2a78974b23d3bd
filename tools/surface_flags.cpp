#include "tools/surface_flags.h"

#include "mesh/error.h"

#include <sstream>

namespace glint::cli {

namespace {

Vec3d parse_point(const std::string& text, const char* flag) {
    std::istringstream in(text);
    Vec3d p;
    char c1 = 0, c2 = 0;
    in >> p.x() >> c1 >> p.y() >> c2 >> p.z();
    if (!in || c1 != ',' || c2 != ',' || !(in >> std::ws).eof())
        throw InputError(std::string(flag) + " \"" + text + "\": expected x,y,z (mm)");
    return p;
}

}  // namespace

void add_surface_flags(CLI::App& cmd, SurfaceOptions& o, const std::string& roi_flag) {
    cmd.add_option_function<double>(
        "--iso", [&o](double v) { o.iso = v; },
        "Volumes: iso value of the surface, in the volume's units (CT bone: about 300 HU; CThead: 1150-1400)");
    cmd.add_option_function<std::string>(
        roi_flag, [&o](const std::string& v) { o.roi = parse_roi(v); },
        "Volumes: extract only inside sphere:x,y,z,r or box:x0,y0,z0,x1,y1,z1 (physical mm)");
    cmd.add_flag("--largest", o.largest, "Volumes: keep only the largest connected surface");
    cmd.add_option_function<std::string>(
           "--seed", [&o](const std::string& v) { o.seed = parse_point(v, "--seed"); },
           "Volumes: keep only the connected surface nearest x,y,z (mm)")
        ->excludes("--largest");
    cmd.add_option("--smooth", o.smooth_iterations,
                   "Volumes: windowed-sinc smoothing iterations (0: none; 10-20 is light)")
        ->capture_default_str();
    cmd.add_option("--passband", o.passband,
                   "Volumes: windowed-sinc pass band (0, 2), lower smooths more")
        ->capture_default_str();
    cmd.add_option("--edge", o.edge_mm,
                   "Volumes: decimate to this mean edge length, mm (0: keep every triangle)")
        ->capture_default_str();
    cmd.add_option(
           "--tolerance", o.tolerance_mm,
           "Volumes: decimation moves the surface at most this far, mm (0: a quarter of the smallest spacing)")
        ->capture_default_str();
}

}  // namespace glint::cli
