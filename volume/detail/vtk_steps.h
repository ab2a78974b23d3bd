// The VTK steps of surface extraction, one method each (internal; see volume/surface.h). VTK
// itself lives in the plugin (volume/plugin/vtk_filters.cpp); these forward to it.
#pragma once

#include "mesh/mesh.h"
#include "mesh/roi.h"
#include "volume/volume.h"

#include <array>
#include <memory>
#include <optional>

namespace glint::detail {

struct PluginSurface;

/// A triangle surface between VTK filters (held by the plugin).
struct VtkSurface {
    std::shared_ptr<PluginSurface> poly;

    [[nodiscard]] std::size_t triangle_count() const;
    /// Voxel index coordinates → physical (mm): p = origin + direction · diag(spacing) · i.
    void to_physical(const VolumeGeometry& geometry);
    /// Drops every triangle with a corner outside the ROI (sphere or box).
    void keep_inside(const Roi& roi);
    /// Keeps one connected component: the one nearest `seed`, else the largest. Returns the
    /// number of components there were.
    std::size_t keep_component(const std::optional<Vec3d>& seed);
    /// Windowed-sinc smoothing (non-shrinking), coordinates normalised, boundaries fixed.
    void smooth(int iterations, double passband);
    /// The triangles as a glint mesh (unused points dropped); `flip` reverses the winding.
    [[nodiscard]] Mesh to_mesh(bool flip) const;
};

/// Flying edges on the voxels [crop[0], crop[1]] (inclusive), output in voxel index
/// coordinates of the whole volume.
[[nodiscard]] VtkSurface contour(const Volume& volume,
                                 const std::array<std::array<std::size_t, 3>, 2>& crop, double iso);

}  // namespace glint::detail
