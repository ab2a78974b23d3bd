// The symmetry plane drawn on a picture of the surface (private to report/; glint asymmetry,
// report/mirror_pictures.h): a thin line where the plane cuts the visible surface, and, in a
// view that sees the plane edge-on, its line across the background too, labelled "symmetry
// plane". The line stays off the regions (their colours and outlines are the finding).
#pragma once

#include "render/frame.h"
#include "render/view.h"
#include "report/detail/canvas.h"
#include "report/detail/labels.h"
#include "report/mirror_pictures.h"

#include <optional>
#include <span>

namespace glint::detail {

/// The colour of the plane's line (no other mark of atlas.png uses it).
inline constexpr Rgb kSymmetryPlane{0.95f, 0.20f, 0.85f};

/// A view sees the plane edge-on when its viewing direction lies within this angle of the
/// plane (degrees): the plane then projects to a line across the whole picture.
inline constexpr double kEdgeOnDeg = 2.0;

/// Where the label of the plane's line goes (picture pixels, text baseline, left aligned).
struct PlaneLabel {
    int x = 0;
    int y = 0;
};

/// The label's text.
inline constexpr std::string_view kSymmetryPlaneLabel = "symmetry plane";

/// Draws the plane on `image` (the frame's size, painted from `frame` of `view` of `mesh`):
/// pixels where the plane runs between a pixel and its neighbour on the same surface (or, for
/// an edge-on view, on the background) take kSymmetryPlane, except those whose triangle
/// touches a region (`region`, per vertex, 0 = none), and those within 3 px of a box of
/// `keep_clear` (the picture's letters and captions). Returns where the label fits on the
/// background beside the line, clear of those boxes, in an edge-on view, if anywhere.
std::optional<PlaneLabel> draw_symmetry_plane(Canvas& image, const Frame& frame, const View& view,
                                              const Mesh& mesh,
                                              std::span<const std::int32_t> region,
                                              const MirrorPictures& plane,
                                              std::span<const PixelBox> keep_clear = {});

/// The label "symmetry plane" at `label` (from draw_symmetry_plane) on a sheet where the
/// picture's top left corner is at (x, y); nothing when there is no label.
void draw_plane_label(Canvas& sheet, int x, int y, const std::optional<PlaneLabel>& label);

/// atlas.png's footer line: "symmetry plane: normal (1, 0, 0), point (0, 0, 0) mm, residual
/// 0.0005 mm".
[[nodiscard]] std::string symmetry_plane_footer(const MirrorPictures& plane,
                                                const std::string& unit);

}  // namespace glint::detail
