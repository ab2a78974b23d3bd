// The table of functions libglint_volume_io.so (volume/plugin/) hands the main program: the
// only bridge to ITK, GDCM and VTK, opened with dlopen by the first run that reads, writes or
// contours a volume (volume/detail/volume_plugin.cpp), so other runs never map them.
//
// The functions take glint's own C++ types: the plugin is built from the same sources with
// the same compiler and standard library as the program, in the same build, and the version
// in the entry point's name changes with any change to this table. No exception crosses the
// boundary: each function returns an error kind and fills `message`; the main side rethrows
// it as glint's own type (so `catch (const InputError&)` sees the program's type, not a copy
// of it in the plugin).
#pragma once

#include "mesh/mesh.h"
#include "mesh/plugin_abi.h"
#include "mesh/roi.h"
#include "volume/detail/itk_io.h"
#include "volume/volume.h"

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>

namespace glint::detail {

/// A VTK surface owned by the plugin (a vtkPolyData behind a pointer the program never reads).
struct PluginSurface;

using VoxelCrop = std::array<std::array<std::size_t, 3>, 2>;

/// Every entry returns None on success; otherwise the kind and a one-line `message`.
struct VolumeIoTable {
    std::size_t table_size;  ///< sizeof(VolumeIoTable) as the plugin was built
    PluginErrorKind (*read)(const std::filesystem::path& path, std::size_t max_voxels,
                            RawVolume& out, std::string& message) noexcept;
    PluginErrorKind (*write)(const RawVolume& volume, const std::filesystem::path& path,
                             std::string& message) noexcept;
    PluginErrorKind (*write_dicom)(const RawVolume& volume, const std::filesystem::path& folder,
                                   std::string& message) noexcept;

    PluginErrorKind (*contour)(const Volume& volume, const VoxelCrop& crop, double iso,
                               PluginSurface*& out, std::string& message) noexcept;
    void (*release)(PluginSurface* surface) noexcept;
    std::size_t (*triangle_count)(const PluginSurface* surface) noexcept;
    PluginErrorKind (*to_physical)(PluginSurface& surface, const VolumeGeometry& geometry,
                                   std::string& message) noexcept;
    PluginErrorKind (*keep_inside)(PluginSurface& surface, const Roi& roi,
                                   std::string& message) noexcept;
    /// `seed` may be null (keep the largest component).
    PluginErrorKind (*keep_component)(PluginSurface& surface, const Vec3d* seed,
                                      std::size_t& components, std::string& message) noexcept;
    PluginErrorKind (*smooth)(PluginSurface& surface, int iterations, double passband,
                              std::string& message) noexcept;
    PluginErrorKind (*to_mesh)(const PluginSurface& surface, bool flip, Mesh& out,
                               std::string& message) noexcept;
};

}  // namespace glint::detail

/// The plugin's one exported symbol; "v1" is the table's version.
#define GLINT_VOLUME_IO_ENTRY "glint_volume_io_table_v1"
extern "C" const glint::detail::VolumeIoTable* glint_volume_io_table_v1();
