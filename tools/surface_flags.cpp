#include "tools/surface_flags.h"

#include "mesh/error.h"

#include <cstdio>
#include <exception>
#include <sstream>
#include <thread>

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

std::string describe(const SurfaceReport& r) {
    char line[320];
    std::snprintf(
        line, sizeof line,
        "%zu x %zu x %zu voxels of %.4g x %.4g x %.4g mm, iso %.6g (data %.6g … %.6g): %zu triangles, %zu of "
        "%zu component(s), %.2f s",
        r.voxels[0], r.voxels[1], r.voxels[2], r.spacing.x(), r.spacing.y(), r.spacing.z(), r.iso,
        static_cast<double>(r.range[0]), static_cast<double>(r.range[1]), r.triangles,
        r.components_kept, r.components_found, r.seconds);
    return line;
}

std::pair<LoadedSurface, LoadedSurface> load_pair(const std::string& reference,
                                                  const std::string& examined,
                                                  const SurfaceOptions& surface) {
    if (is_volume_path(reference) || is_volume_path(examined))
        return {load_surface(reference, surface), load_surface(examined, surface)};
    LoadedSurface exa;
    std::exception_ptr exa_error;
    std::thread other([&] {
        try {
            exa = load_surface(examined, surface);
        } catch (...) {
            exa_error = std::current_exception();
        }
    });
    LoadedSurface ref;
    try {
        ref = load_surface(reference, surface);
    } catch (...) {
        other.join();
        throw;
    }
    other.join();
    if (exa_error) std::rethrow_exception(exa_error);
    return {std::move(ref), std::move(exa)};
}

}  // namespace glint::cli
