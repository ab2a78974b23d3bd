// The scale bar every view panel, close-up and per-view picture carries (private to report/):
// a round length of the mesh unit (1, 2 or 5 × 10^k) drawn at the picture's own scale, so a
// reader can measure a region on the page. Orthographic pictures have one scale at every
// depth; a perspective picture's bar is true at the depth where its View::footprint is given
// (the nearest surface of the framed sphere), and its label says so.
#pragma once

#include "render/view.h"
#include "report/detail/canvas.h"
#include "report/detail/labels.h"

#include <string>

namespace glint::detail {

/// The bar's own colour: no colour of the shape map, the hatching or the text is this yellow
/// (blue channel 0), so the bar is found by its pixels (tests do).
inline constexpr Rgb kScaleBarColour{1.0f, 0.82f, 0.0f};

/// Thickness of the bar, pixels (drawn with a one-pixel dark border around it).
inline constexpr int kScaleBarThickness = 4;

struct ScaleBar {
    double length = 0.0;  ///< mesh units: 1, 2 or 5 × 10^k
    int pixels = 0;       ///< the bar's length on the picture
    std::string label;    ///< "10 mm"; "10 mm at front" for a perspective picture
};

/// The largest of 1, 2, 5 × 10^k that is at most `x` (x > 0).
[[nodiscard]] double round_length_at_most(double x);

/// The bar's label: the length as it reads ("0.5 mm", "20 mm", "1e+03 units") and, for a
/// perspective picture, " at front" (true at the nearest surface of the framed sphere).
[[nodiscard]] std::string scale_bar_label(double length, const std::string& unit, bool perspective);

/// Mesh units per pixel of a picture rendered from `view`: the orthographic camera's scale;
/// for a perspective camera, the scale at the nearest surface of the framed sphere
/// (View::footprint, which render/view.h defines there).
[[nodiscard]] double picture_units_per_px(const View& view);

/// The longest round bar of at most `max_pixels` at `units_per_px`; pixels = 0 when even the
/// shortest round length would not fit one pixel (a scale that is not finite or not positive).
[[nodiscard]] ScaleBar scale_bar(double units_per_px, int max_pixels, const std::string& unit,
                                 bool perspective = false);

/// The bar of a picture of `view` (at most a quarter of its width), with `unit`.
[[nodiscard]] ScaleBar view_scale_bar(const View& view, const std::string& unit);

/// Draws the bar with its right end at x = `right` and its bottom row at y = `bottom`, the
/// label above it, right-aligned. Nothing is drawn for a bar of 0 pixels.
void draw_scale_bar(Canvas& dst, int right, int bottom, const ScaleBar& bar);

/// What draw_view_scale_bar covers (bar and label), in the picture's pixels: region numbers
/// keep off it.
[[nodiscard]] PixelBox view_scale_bar_box(const View& view, const std::string& unit);

/// The bar of `view` in the bottom right corner of a picture of that view pasted at (x0, y0).
void draw_view_scale_bar(Canvas& dst, int x0, int y0, const View& view, const std::string& unit);

}  // namespace glint::detail
