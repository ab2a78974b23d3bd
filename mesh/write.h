// Writing meshes: binary PLY with colour + named scalars (MeshLab "quality"/CloudCompare
// scalar fields), VTK legacy with point-data arrays (ParaView, 3D Slicer).
// Files are written to a temporary name in the same folder and renamed into place.
#pragma once

#include "mesh/mesh.h"

#include <filesystem>

namespace glint {

struct WriteOptions {
    bool write_normals = true;
    bool write_colors = true;   ///< when mesh.colors is set
    bool write_scalars = true;  ///< every ScalarField as a float property
    bool write_labels = true;   ///< labels as an int property "label"
};

/// Binary little-endian PLY. \throw IoError on any write failure (nothing left behind).
void write_ply(const Mesh& mesh, const std::filesystem::path& path, const WriteOptions& options = {});

/// VTK legacy POLYDATA (binary big-endian), scalars and labels as POINT_DATA arrays,
/// colours as COLOR_SCALARS. \throw IoError on any write failure.
void write_vtk(const Mesh& mesh, const std::filesystem::path& path, const WriteOptions& options = {});

/// Writes by extension (.ply, .vtk); \throw InputError for another extension.
void write_mesh(const Mesh& mesh, const std::filesystem::path& path, const WriteOptions& options = {});

}  // namespace glint
