// Helpers the mesh writers (mesh/write.cpp, mesh/write_vtk.cpp) share.
#pragma once

#include "mesh/mesh.h"

#include <filesystem>
#include <string>

namespace glint::detail {

/// Property / array names are single words in PLY and VTK: anything else becomes '_'.
[[nodiscard]] std::string safe_name(const std::string& name);

/// \throw InputError when a per-vertex array's size differs from the vertex count or a
/// triangle uses a vertex that does not exist (names the file being written).
void check_sizes(const Mesh& mesh, const std::filesystem::path& path);

}  // namespace glint::detail
