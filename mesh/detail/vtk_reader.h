// glint's own reader for VTK legacy POLYDATA files (ASCII and BINARY big-endian bodies).
//
// Reads POINTS (any numeric type), POLYGONS (fan-split) and TRIANGLE_STRIPS (converted), in the
// classic "n size" layout and in the VTK 5.1 OFFSETS/CONNECTIVITY layout; skips VERTICES and
// LINES (reported). POINT_DATA: 1-component SCALARS and FIELD arrays become ScalarFields (an
// integer "label" array becomes Mesh::labels), NORMALS and COLOR_SCALARS are kept; CELL_DATA,
// FIELD blocks elsewhere (3D Slicer writes "MaterialNames" string arrays), lookup tables,
// vectors, tensors and METADATA blocks are skipped. Spec: "VTK File Formats" (Kitware, VTK
// User's Guide, legacy format section).
#pragma once

#include "mesh/io.h"
#include "mesh/mesh.h"

#include <span>
#include <string>

namespace glint::detail {

/// Parses a VTK legacy file held in memory. `source` names the file in messages.
/// Fills report.format ("vtk-ascii" / "vtk-binary"), file_vertices, file_triangles,
/// split_polygons and warnings.
/// Counts are checked against the bytes left and the triangles against
/// options.max_triangles before work; the loops poll cancellation (throw Cancelled).
/// \throw InputError not POLYDATA, unknown keyword or type, truncated data (section named,
///        line for ASCII, byte offset for BINARY), cell index past the point count (cell named)
[[nodiscard]] Mesh read_vtk(std::span<const char> data, const std::string& source,
                            LoadReport& report, const LoadOptions& options = {});

}  // namespace glint::detail
