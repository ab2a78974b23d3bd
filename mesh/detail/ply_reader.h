// glint's own PLY reader (ASCII, binary little endian, binary big endian).
//
// One pass over a file held in memory, no allocation per vertex or face. Reads vertex x, y, z
// (any numeric type), optional nx, ny, nz, red, green, blue, an integer "label" (into
// Mesh::labels) and every other vertex scalar property as a ScalarField; faces from the
// "vertex_indices" / "vertex_index" list (polygons fan-split and counted); every other element
// (e.g. the Stanford scans' "range_grid") is skipped in all three encodings.
#pragma once

#include "mesh/io.h"
#include "mesh/mesh.h"

#include <span>
#include <string>

namespace glint::detail {

/// Parses the PLY file `data` (its whole content). `source` names the file in messages.
/// Fills report.format, file_vertices, file_triangles, split_polygons and warnings.
/// Counts are checked against the bytes left and the triangles against
/// options.max_triangles before work; the loops poll cancellation (throw Cancelled).
/// \throw InputError malformed header, truncated body (element and index named), a face index
///        past the end of the vertex list (face id named), unparsable ASCII (line named)
[[nodiscard]] Mesh read_ply(std::span<const char> data, const std::string& source,
                            LoadReport& report, const LoadOptions& options = {});

}  // namespace glint::detail
