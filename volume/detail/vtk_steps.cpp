// vtk_steps.h's steps, answered by the plugin. The cancel checks stay here, after the long
// steps, because the request to stop lives in the program's mesh/cancel, not in the plugin.
#include "volume/detail/vtk_steps.h"

#include "mesh/cancel.h"
#include "volume/detail/volume_plugin.h"

namespace glint::detail {

std::size_t VtkSurface::triangle_count() const {
    return poly ? volume_io_plugin().triangle_count(poly.get()) : 0;
}

VtkSurface contour(const Volume& volume, const std::array<std::array<std::size_t, 3>, 2>& crop,
                   double iso) {
    const VolumeIoTable& io = volume_io_plugin();
    PluginSurface* surface = nullptr;
    call_volume_io([&](const VolumeIoTable&, std::string& message) {
        return io.contour(volume, crop, iso, surface, message);
    });
    VtkSurface out{std::shared_ptr<PluginSurface>(surface, io.release)};
    throw_if_cancelled();
    return out;
}

void VtkSurface::to_physical(const VolumeGeometry& geometry) {
    call_volume_io([&](const VolumeIoTable& io, std::string& message) {
        return io.to_physical(*poly, geometry, message);
    });
}

void VtkSurface::keep_inside(const Roi& roi) {
    call_volume_io([&](const VolumeIoTable& io, std::string& message) {
        return io.keep_inside(*poly, roi, message);
    });
}

std::size_t VtkSurface::keep_component(const std::optional<Vec3d>& seed) {
    std::size_t components = 0;
    call_volume_io([&](const VolumeIoTable& io, std::string& message) {
        return io.keep_component(*poly, seed ? &*seed : nullptr, components, message);
    });
    return components;
}

void VtkSurface::smooth(int iterations, double passband) {
    call_volume_io([&](const VolumeIoTable& io, std::string& message) {
        return io.smooth(*poly, iterations, passband, message);
    });
    throw_if_cancelled();
}

Mesh VtkSurface::to_mesh(bool flip) const {
    Mesh mesh;
    call_volume_io([&](const VolumeIoTable& io, std::string& message) {
        return io.to_mesh(*poly, flip, mesh, message);
    });
    return mesh;
}

}  // namespace glint::detail
