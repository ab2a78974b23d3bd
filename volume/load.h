// One entry point for "a surface from a file": a mesh file is loaded as mesh/io.h does; a
// volume (by extension, or a DICOM folder) is read and its iso-surface extracted with the
// surface options. Every command and scenario that takes a mesh takes a volume this way.
#pragma once

#include "mesh/io.h"
#include "volume/surface.h"

#include <filesystem>
#include <optional>

namespace glint {

struct LoadedSurface {
    Mesh mesh;
    LoadReport report;  ///< for a volume: path, format "volume-<format>", notes as warnings
    std::optional<SurfaceReport> surface;  ///< set when the surface came from a volume
    std::optional<VolumeGeometry> geometry;
};

/// Loads a mesh file or extracts the surface of a volume.
/// \throw InputError a volume without an iso value (the message gives the data range and asks
/// for --iso), surface options given for a mesh file, and whatever load_mesh, read_volume and
/// extract_surface throw.
[[nodiscard]] LoadedSurface load_surface(const std::filesystem::path& path,
                                         const SurfaceOptions& surface,
                                         const LoadOptions& options = {});

}  // namespace glint
