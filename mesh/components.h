// Connectivity over a mesh: union-find, connected groups of selected vertices, borders.
// One implementation for validation (components of a mesh), regions (damaged vertices),
// coverage (unseen patches) and hole filling.
#pragma once

#include "mesh/mesh.h"

#include <cstdint>
#include <span>
#include <vector>

namespace glint {

/// Disjoint sets over 0…n−1 with path halving (no ranks: the meshes' edge order keeps the
/// trees shallow enough, and halving alone is amortised logarithmic).
class UnionFind {
  public:
    explicit UnionFind(std::size_t n);
    /// Representative of x's set.
    [[nodiscard]] std::uint32_t find(std::uint32_t x);
    /// Joins the sets of a and b.
    void unite(std::uint32_t a, std::uint32_t b);

  private:
    std::vector<std::uint32_t> parent_;
};

/// Groups of the vertices with mask[v] != 0 connected through mesh edges whose two ends are
/// both selected. component[v] = group id (0-based, in order of the lowest vertex id) or −1
/// for unselected vertices. Returns the number of groups. \pre mask.size() = vertex count.
std::size_t masked_components(const Mesh& mesh, std::span<const std::uint8_t> mask,
                              std::vector<std::int32_t>& component);

/// The triangles around every vertex, ascending: triangles[offsets[v] … offsets[v + 1]) are
/// those that use v (a triangle using v twice is listed twice). Built by a counting sort, O(n).
struct VertexTriangles {
    std::vector<std::uint32_t> offsets;  ///< vertex count + 1 entries
    std::vector<std::uint32_t> triangles;

    /// How many triangles around `a` also use `b` (the triangles sharing edge a–b).
    [[nodiscard]] std::size_t sharing(const Mesh& mesh, std::uint32_t a, std::uint32_t b) const;
};
[[nodiscard]] VertexTriangles vertex_triangles(const Mesh& mesh);

/// 1 for every vertex on a border edge (an edge used by exactly one triangle), else 0.
[[nodiscard]] std::vector<std::uint8_t> border_vertices(const Mesh& mesh);

/// The total length of the border edges (used by exactly one triangle), mesh units: 0 for a
/// closed surface.
[[nodiscard]] double border_length(const Mesh& mesh);

}  // namespace glint
