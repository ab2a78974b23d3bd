// Checks made on a file's bytes before assimp reads it, so that hostile input is refused with
// our one-line error instead of crashing, hanging or exhausting memory inside assimp:
//   glTF / GLB: JSON nesting, node nesting (assimp recurses per level and overflows the stack
//               a few thousand levels down), node cycles, instance expansion (a node shared
//               by several parents is copied for each path: a DAG of 40 levels is 2^40
//               copies) and the triangles all instances add up to, from the accessor counts;
//   OFF:        vertex and face counts against the file size;
//   OBJ:        face lines against the triangle budget.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace glint::detail {

inline constexpr int kMaxGltfNodeDepth = 64;                 ///< node nesting levels
inline constexpr std::uint64_t kMaxGltfInstances = 100'000;  ///< node instances after expansion
inline constexpr int kMaxJsonDepth = 128;                    ///< JSON object/array nesting

/// Dispatches on the extension (".gltf", ".glb", ".off", ".obj", lower case) and the GLB
/// signature; other formats pass unchecked.
/// \throw InputError naming the file and the limit that was exceeded, or the malformed part
void check_before_assimp(std::span<const char> data, const std::string& ext,
                         const std::string& source, std::uint64_t max_triangles);

/// The checks on a glTF JSON document (the text of a .gltf file or a GLB's JSON chunk).
void check_gltf_json(std::span<const char> json, const std::string& source,
                     std::uint64_t max_triangles);

}  // namespace glint::detail
