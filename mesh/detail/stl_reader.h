// glint's own STL reader: binary fast path and ASCII with line numbers in every message.
//
// STL is triangle soup: every facet carries its own three corners. The reader returns that
// soup (3 vertices per facet); load_mesh welds it with weld_vertices (mesh/weld.h).
#pragma once

#include "mesh/io.h"
#include "mesh/mesh.h"

#include <span>
#include <string>

namespace glint::detail {

/// True when `data` is a binary STL: its size is exactly 84 + 50·n for the facet count n in
/// the header, and it does not read as ASCII STL (a binary header may start with "solid").
[[nodiscard]] bool is_binary_stl(std::span<const char> data);

/// Parses an STL file (binary or ASCII, chosen by is_binary_stl) into triangle soup.
/// Fills report.format, file_vertices (3 per facet), file_triangles, split_polygons, warnings.
/// Counts are checked against the bytes left and the triangles against
/// options.max_triangles before work; the loops poll cancellation (throw Cancelled).
/// \throw InputError size that does not match the facet count (both numbers named), ASCII
///        syntax error (line, expected token and the line's text), non-finite coordinate
///        (facet and corner named)
[[nodiscard]] Mesh read_stl(std::span<const char> data, const std::string& source,
                            LoadReport& report, const LoadOptions& options = {});

}  // namespace glint::detail
