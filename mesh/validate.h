// Mesh validation: hard errors throw, the rest is reported.
#pragma once

#include "mesh/mesh.h"

#include <cstddef>
#include <string>
#include <vector>

namespace glint {

struct ValidationReport {
    std::size_t vertices = 0;
    std::size_t triangles = 0;
    std::size_t boundary_edges = 0;      ///< edges used by one triangle
    std::size_t non_manifold_edges = 0;  ///< edges used by more than two triangles
    std::size_t components = 0;          ///< connected components (by shared vertices)
    std::size_t unused_vertices = 0;
    bool is_closed = false;  ///< no boundary and no non-manifold edge
    Bounds bounds;
    double area = 0.0;
    std::vector<std::string> findings;  ///< human-readable, one per problem kind
};

/// Checks hard invariants and throws InputError naming `source` (a file name or a label)
/// on the first of: no vertices, no triangles, non-finite coordinate (vertex id and value),
/// triangle index out of range (triangle id, index, vertex count), zero extent.
void check_mesh(const Mesh& mesh, const std::string& source);

/// check_mesh + topology statistics (boundary, non-manifold, components).
[[nodiscard]] ValidationReport validate_mesh(const Mesh& mesh, const std::string& source);

/// Connected component id of every vertex (by triangles); returns the number of components.
std::size_t connected_components(const Mesh& mesh, std::vector<std::uint32_t>& component_of_vertex);

}  // namespace glint
