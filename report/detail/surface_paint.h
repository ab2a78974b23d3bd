// A rendered view of the reference surface painted for people (private to report/):
//
//   colour   the signed shape change on the diverging map (blue loss, white 0, red gain),
//            symmetric range ±limit mesh units;
//   shading  Lambert from the rendered normal, one light from the upper left behind the
//            viewer (the paper's fixed light, render/shade.h), so the surface form shows;
//   unseen   vertices no view saw: grey with dark diagonal hatching;
//   regions  outlined where a pixel's region differs from a neighbour's, with an anchor per
//            region (the region pixel nearest its pixel centroid) for its number.
//
// Per-pixel values come from the frame's primitive ids: the pixel centre's barycentric
// weights in its triangle (the ray caster's, Frame::barycentric, where the frame has them;
// else from the projected corners, exact for orthographic views) interpolate the per-vertex
// distance, and the corner with the largest weight gives the
// region and the seen flag, so outlines follow the vertices' dual cells.
#pragma once

#include "mesh/mesh.h"
#include "render/frame.h"
#include "render/view.h"
#include "report/detail/canvas.h"

#include <cstdint>
#include <span>
#include <vector>

namespace glint::detail {

/// The shade of a surface the light does not reach: the back of an open surface (its normals
/// face away from the viewer) is drawn this dark, which the legend shows.
inline constexpr float kAmbientShade = 0.32f;

/// The colour of an unchanged surface seen from behind: the legend's swatch.
[[nodiscard]] Rgb back_face_colour();

/// Per-vertex fields a picture shows (each one value per reference vertex).
struct SurfaceFields {
    std::span<const float> distance;       ///< signed shape change, mesh units (NaN = unknown)
    std::span<const std::int32_t> region;  ///< region id, 0 = none
    /// 0 = unseen (hatched), 1 = seen and compared, 2 = seen but not compared (hatched the
    /// other way: an open border of either surface, or the examined scan did not reach it)
    std::span<const std::uint8_t> seen;
};

/// Where a region's number goes in one picture.
struct RegionAnchor {
    std::int32_t id = 0;
    int x = 0;
    int y = 0;
    std::size_t pixels = 0;  ///< pixels of the region visible in the picture
    int min_x = 0, min_y = 0, max_x = 0, max_y = 0;  ///< bounding box of those pixels
};

struct PaintedSurface {
    Canvas image;                       ///< RGB, 8 bits per channel, the frame's size
    std::vector<RegionAnchor> anchors;  ///< regions visible, by id
};

/// What one view measured, per pixel of the frame painted (report/detail/measured_pixels.h maps
/// a ViewMeasurement onto it). With it a picture shows the view's own measurement instead of
/// the per-vertex distance: compared pixels its signed depth (pale where within the floor),
/// reference pixels with no examined surface behind them hatched violet, examined surface
/// beyond the reference outline green, the rest of the surface, and surface the decision
/// does not compare (SurfaceFields::seen 2), hatched as not compared.
struct MeasuredPixels {
    std::vector<float> depth;          ///< signed depth along the view ray; NaN: not compared
    std::vector<std::uint8_t> status;  ///< MeasuredStatus (report/view_measurements.h)
    std::vector<std::uint8_t> beyond;  ///< 1 where the view measured beyond its floor
};

/// How much paler a compared pixel within the floor is drawn: its colour mixed this far
/// towards the map's white.
inline constexpr float kWithinFloorPale = 0.6f;

struct PaintStyle {
    double limit = 1.0;     ///< colour range ±limit (mesh units), > 0
    int outline_width = 2;  ///< 1: the region side of the contour only; 2: both sides
    int hatch_period = 7;   ///< pixels between hatching stripes
    Rgb background = kBackground;
    /// The view's own measurement (sized as the frame), or null: the per-vertex fields.
    const MeasuredPixels* measured = nullptr;
};

/// Paints `frame` (rendered from `view` of `mesh`) as described above.
/// \pre fields sized as the mesh's vertices; frame from a renderer of `mesh`.
[[nodiscard]] PaintedSurface paint_surface(const Mesh& mesh, const Frame& frame, const View& view,
                                           const SurfaceFields& fields, const PaintStyle& style);

}  // namespace glint::detail
