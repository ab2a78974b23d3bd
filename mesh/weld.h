// Repairs on raw triangle data: welding of triangle soup, degenerate/duplicate triangles,
// unused vertices. Every repair is counted (never silent).
#pragma once

#include "mesh/mesh.h"

#include <cstddef>
#include <vector>

namespace glint {

struct RepairCounts {
    std::size_t welded_vertices = 0;
    std::size_t degenerate_triangles = 0;
    std::size_t duplicate_triangles = 0;
    std::size_t unused_vertices = 0;
};

/// Merges vertices with bit-identical positions (hash on the coordinates; -0 == +0).
/// Per-vertex attributes of the first occurrence are kept. Returns new id of every old vertex.
std::vector<std::uint32_t> weld_vertices(Mesh& mesh, RepairCounts& counts);

/// Drops triangles that repeat a vertex or have zero area, and exact duplicates
/// (same vertex set, same or opposite winding is kept apart: only same set+winding drops).
void drop_degenerate_triangles(Mesh& mesh, RepairCounts& counts);

/// Drops vertices no triangle references; returns new id of every old vertex
/// (kInvalidVertex for dropped ones). Per-vertex attributes follow.
std::vector<std::uint32_t> drop_unused_vertices(Mesh& mesh, RepairCounts& counts);

inline constexpr std::uint32_t kInvalidVertex = 0xFFFFFFFFu;

/// Keeps only vertices with keep[v] and re-indexes; triangles touching a dropped vertex are
/// dropped. Returns new id of every old vertex (kInvalidVertex when dropped).
std::vector<std::uint32_t> compact_vertices(Mesh& mesh, const std::vector<bool>& keep);

}  // namespace glint
