// Reordering for memory/rasteriser locality (meshoptimizer), with the map back to the
// original vertex ids so per-vertex results can be reported in the input's numbering.
#pragma once

#include "mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace glint {

struct ReorderMap {
    /// original_vertex[new_id] = id in the mesh before reordering.
    std::vector<std::uint32_t> original_vertex;
    /// original_triangle[new_id] = id before reordering.
    std::vector<std::uint32_t> original_triangle;
};

/// Reorders triangles (vertex cache + overdraw) and then vertices (fetch order) in place;
/// every per-vertex array follows. Returns the map to the original ids.
ReorderMap reorder_for_locality(Mesh& mesh);

/// Scatters per-vertex values of a reordered mesh back to original vertex order.
[[nodiscard]] std::vector<float> to_original_order(const ReorderMap& map,
                                                   const std::vector<float>& values);

}  // namespace glint
