// The plugin's entry point: the table of volume/plugin/volume_io_abi.h, each entry a guard
// that turns an exception into (kind, message) so that none unwinds through dlopen's
// boundary into the program.
#include "mesh/error.h"
#include "volume/plugin/itk_side.h"
#include "volume/plugin/volume_io_abi.h"
#include "volume/plugin/vtk_filters.h"

namespace glint::detail {
namespace {

PluginErrorKind read(const std::filesystem::path& path, std::size_t max_voxels, RawVolume& out,
                     std::string& message) noexcept {
    return plugin_guarded(message, [&] { out = itk_side::read(path, max_voxels); });
}

PluginErrorKind write(const RawVolume& volume, const std::filesystem::path& path,
                      std::string& message) noexcept {
    return plugin_guarded(message, [&] { itk_side::write(volume, path); });
}

PluginErrorKind write_dicom(const RawVolume& volume, const std::filesystem::path& folder,
                            std::string& message) noexcept {
    return plugin_guarded(message, [&] { itk_side::write_dicom(volume, folder); });
}

PluginErrorKind contour(const Volume& volume, const VoxelCrop& crop, double iso,
                        PluginSurface*& out, std::string& message) noexcept {
    return plugin_guarded(
        message, [&] { out = new PluginSurface(vtk_filters::contour(volume, crop, iso)); });
}

void release(PluginSurface* surface) noexcept { delete surface; }

std::size_t triangle_count(const PluginSurface* surface) noexcept {
    return surface ? vtk_filters::triangle_count(*surface) : 0;
}

PluginErrorKind to_physical(PluginSurface& surface, const VolumeGeometry& geometry,
                            std::string& message) noexcept {
    return plugin_guarded(message, [&] { vtk_filters::to_physical(surface, geometry); });
}

PluginErrorKind keep_inside(PluginSurface& surface, const Roi& roi, std::string& message) noexcept {
    return plugin_guarded(message, [&] { vtk_filters::keep_inside(surface, roi); });
}

PluginErrorKind keep_component(PluginSurface& surface, const Vec3d* seed, std::size_t& components,
                               std::string& message) noexcept {
    return plugin_guarded(message,
                          [&] { components = vtk_filters::keep_component(surface, seed); });
}

PluginErrorKind smooth(PluginSurface& surface, int iterations, double passband,
                       std::string& message) noexcept {
    return plugin_guarded(message, [&] { vtk_filters::smooth(surface, iterations, passband); });
}

PluginErrorKind to_mesh(const PluginSurface& surface, bool flip, Mesh& out,
                        std::string& message) noexcept {
    return plugin_guarded(message, [&] { out = vtk_filters::to_mesh(surface, flip); });
}

constexpr VolumeIoTable kTable{
    sizeof(VolumeIoTable), read,        write,       write_dicom,    contour, release,
    triangle_count,        to_physical, keep_inside, keep_component, smooth,  to_mesh};

}  // namespace
}  // namespace glint::detail

extern "C" __attribute__((visibility("default"))) const glint::detail::VolumeIoTable*
glint_volume_io_table_v1() {
    return &glint::detail::kTable;
}
