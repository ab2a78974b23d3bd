// A region of interest on a reference surface: the part a fit uses (a stable region) or the
// part a sweep analyses (DESIGN.md: "analysis of only part of a surface must be possible").
//
// Three shapes, one type, one parser for the command line and scenario files:
//   sphere:x,y,z,r               points within r of the centre (reference coordinates)
//   box:x0,y0,z0,x1,y1,z1        points inside the axis-aligned box
//   mask:FILE.ply[:SCALAR]       reference vertices whose label (or SCALAR) is non-zero in a
//                                mesh with the reference's vertices (read by read_roi_mask)
#pragma once

#include "mesh/geometry.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

struct Roi {
    enum class Shape { Sphere, Box, VertexMask };
    Shape shape = Shape::Sphere;
    Vec3d center{0, 0, 0};  ///< sphere
    double radius = 0.0;    ///< sphere, mesh units
    Vec3d min{0, 0, 0};     ///< box
    Vec3d max{0, 0, 0};     ///< box
    /// VertexMask: one entry per reference vertex, non-zero inside. Empty until
    /// read_roi_mask() (or the caller) fills it.
    std::vector<std::uint8_t> vertex_mask;
    std::filesystem::path mask_file;  ///< VertexMask: where the mask came from
    std::string mask_property;        ///< VertexMask: "label" or the scalar's name

    /// Whether reference vertex `vertex` at position `p` lies inside.
    /// \pre for VertexMask, `vertex` < vertex_mask.size().
    [[nodiscard]] bool contains(std::size_t vertex, const Vec3d& p) const;
    /// Whether a point lies inside a sphere or box ROI; for a VertexMask use contains().
    [[nodiscard]] bool contains_point(const Vec3d& p) const;
    /// Whether the mask still has to be read from mask_file.
    [[nodiscard]] bool needs_mask() const {
        return shape == Shape::VertexMask && vertex_mask.empty();
    }
};

/// Parses "sphere:x,y,z,r", "box:x0,y0,z0,x1,y1,z1" or "mask:FILE[:SCALAR]" (the mask is
/// not read here: see read_roi_mask). \throw InputError naming the text and the rule.
[[nodiscard]] Roi parse_roi(const std::string& text);

/// The text parse_roi() reads back ("mask:FILE:PROPERTY" for a mask).
[[nodiscard]] std::string to_string(const Roi& roi);

/// Reads a VertexMask ROI's file: a mesh with exactly `vertex_count` vertices (kept unwelded,
/// in file order) whose labels, or the named scalar, are non-zero on the region.
/// \throw InputError wrong vertex count, no such property, an empty mask; IoError.
void read_roi_mask(Roi& roi, std::size_t vertex_count);

}  // namespace glint
