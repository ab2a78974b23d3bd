#include "volume/load.h"

#include "mesh/error.h"
#include "mesh/front_end.h"

#include <cstdio>

namespace glint {

LoadedSurface load_surface(const std::filesystem::path& path, const SurfaceOptions& surface,
                           const LoadOptions& options) {
    LoadedSurface out;
    if (!is_volume_path(path)) {
        if (surface.iso || surface.any())
            throw InputError(
                "mesh \"" + path.string() +
                "\": surface options (iso, surface ROI, largest, seed, smooth, edge) apply to volumes, "
                "this is a mesh file");
        LoadedMesh m = load_mesh(path, options);
        out.mesh = std::move(m.mesh);
        out.report = std::move(m.report);
        return out;
    }
    const Volume volume = read_volume(path);
    if (!surface.iso) {
        const auto range = volume.range();
        char text[96];
        std::snprintf(text, sizeof text, "%.6g … %.6g", static_cast<double>(range[0]),
                      static_cast<double>(range[1]));
        throw InputError("volume \"" + path.string() + "\": a volume needs " +
                         spell_option("iso", "VALUE") + " (scenario key iso) to give a " +
                         "surface; its data range is " + text);
    }
    ExtractedSurface s = extract_surface(volume, surface);
    out.mesh = std::move(s.mesh);
    out.report.path = path;
    out.report.format = "volume-" + volume.format;
    out.report.file_vertices = out.mesh.vertex_count();
    out.report.file_triangles = out.mesh.triangle_count();
    out.surface = std::move(s.report);
    out.geometry = volume.geometry;
    return out;
}

}  // namespace glint
