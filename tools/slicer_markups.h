// Slicer's markups as the Slicer module receives them: an ROI passed as text, and point lists
// written by Slicer as markups files (tools/slicer_module.h).
//
// Coordinates. Slicer keeps its scene in RAS; a CLI parameter's coordinateSystem attribute
// says how the module wants a markup: "lps" negates x and y (vtkMRMLMarkupsROINode::WriteCLI,
// vtkMRMLMarkupsNode::WriteCLI), and a point file states its own system (the "coordinateSystem"
// key of a .mrk.json markup, the "# CoordinateSystem = " line of a .fcsv; LPS when absent, as
// Slicer's markups storage node assumes). The module's description asks for "lps", and
// everything here is returned in LPS: the space Slicer writes models and volumes in, which is
// the space the module runs in.
#pragma once

#include "mesh/geometry.h"
#include "mesh/roi.h"

#include <filesystem>
#include <string>
#include <vector>

namespace glint::cli {

/// An ROI as Slicer passes a <region>: "cx,cy,cz,rx,ry,rz" (centre and half sizes, mm), as a
/// box ROI.
/// \throw InputError not six numbers, a radius that is not positive, or a rotated ROI (Slicer
/// then appends nine axis components: glint's regions are axis-aligned; identity axes pass).
[[nodiscard]] Roi parse_slicer_region(const std::string& text);

/// Whether `text` is a Slicer region ("cx,cy,…" numbers) rather than glint's own region text
/// ("sphere:…", "box:…", "mask:…").
[[nodiscard]] bool is_slicer_region(const std::string& text);

/// The control points of a markups file written by Slicer (.mrk.json, or .fcsv), in file
/// order, in LPS.
/// \throw IoError cannot open; InputError naming the file and the point or line for JSON that
/// is not a markups file, a line that is not "id,x,y,z,…", a point without a position, an
/// unknown coordinate system, or no point at all.
[[nodiscard]] std::vector<Vec3d> read_markups_points(const std::filesystem::path& path);

}  // namespace glint::cli
