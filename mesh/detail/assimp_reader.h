// Loading through assimp (OBJ, OFF, glTF/GLB, PLY, STL and whatever else assimp reads).
//
// Only aiProcess_Triangulate is applied: no JoinIdenticalVertices, so welding is done and
// counted by load_mesh like for every other reader. Node transforms are applied, every mesh of
// the scene is appended; point and line primitives are skipped and counted.
#pragma once

#include "mesh/io.h"
#include "mesh/mesh.h"

#include <filesystem>
#include <string>

namespace glint::detail {

/// Reads `path` with assimp. `source` names the file in messages.
/// Fills report.format (the lower-case extension), file_vertices, file_triangles, warnings.
/// \throw InputError assimp's own message when it cannot read the file
/// Triangles beyond options.max_triangles are refused; cancellation is polled between meshes
/// (not inside assimp's own import: callers check the file first, see scene_check.h).
[[nodiscard]] Mesh read_assimp(const std::filesystem::path& path, const std::string& source,
                               LoadReport& report, const LoadOptions& options = {});

}  // namespace glint::detail
