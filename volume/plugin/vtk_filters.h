// The VTK steps of surface extraction inside the plugin, one function each (the program
// reaches them through volume/detail/vtk_steps.h; their meaning is documented there).
#pragma once

#include "volume/plugin/volume_io_abi.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace glint::detail {

struct PluginSurface {
    vtkSmartPointer<vtkPolyData> poly;
};

namespace vtk_filters {

[[nodiscard]] PluginSurface contour(const Volume& volume, const VoxelCrop& crop, double iso);
[[nodiscard]] std::size_t triangle_count(const PluginSurface& surface);
void to_physical(PluginSurface& surface, const VolumeGeometry& geometry);
void keep_inside(PluginSurface& surface, const Roi& roi);
[[nodiscard]] std::size_t keep_component(PluginSurface& surface, const Vec3d* seed);
void smooth(PluginSurface& surface, int iterations, double passband);
[[nodiscard]] Mesh to_mesh(const PluginSurface& surface, bool flip);

}  // namespace vtk_filters
}  // namespace glint::detail
