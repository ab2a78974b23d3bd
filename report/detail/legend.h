// The legend every picture carries (private to report/): a colour bar of the signed shape
// change with ticks and its unit, the shape floor marked on it, swatches for unseen surface
// and region outlines, the thresholds and floors, and the regions by number.
#pragma once

#include "decision/regions.h"
#include "report/detail/canvas.h"

#include <string>
#include <vector>

namespace glint::detail {

/// A region's kind in words: "dent", "bump", "missing surface"; of a surface against its
/// mirror image (`mirror`, glint asymmetry), the finding's: "less", "more", "no mirrored
/// surface".
[[nodiscard]] std::string region_kind_name(const Region& region, bool mirror = false);

/// A region's line in the legend: "3  dent  −0.41 mm, 12.3 mm²"; a missing-surface region
/// has no depth to give (report.json's depth is null): "5  missing surface, 2.1 mm²".
/// `mirror`: the kind as region_kind_name gives it ("3  less  −0.41 mm, 12.3 mm²").
[[nodiscard]] std::string region_legend_line(const Region& region, const std::string& unit,
                                             bool mirror = false);

struct LegendContent {
    double limit = 1.0;        ///< colour range ±limit, mesh units
    std::string limit_source;  ///< why this range ("largest region peak", …)
    double shape_floor = 0.0;  ///< marked on the bar when > 0 and inside the range
    std::string unit;          ///< length unit shown ("mm"; "units" when unknown)
    bool roi = false;          ///< the sweep analysed a part only: outside it counts as unseen
    /// The picture shows one view's own measurement (report/view_measurements.h): the bar is
    /// its signed depth along the view ray, and the swatches its statuses and the pale floor.
    bool measured = false;
    /// The surface against its mirror image (glint asymmetry): the bar's ends read "more" and
    /// "less than the mirrored other side".
    bool mirror = false;
    /// A swatch names the symmetry plane's line (report/detail/symmetry_plane_trace.h).
    bool plane_line = false;
    std::vector<std::string> lines;    ///< thresholds and floors, one per line
    std::vector<std::string> regions;  ///< "1 dent −0.41 mm, 12.3 mm²", in id order
};

/// Height of the title line above every picture, pixels.
inline constexpr int kTitleHeight = 30;

/// Width of the legend panel, pixels.
inline constexpr int kLegendWidth = 290;

/// The swatch rows' labels as drawn (the legend's font, each from kSwatchLabelX of the panel
/// on): every one fits the panel (tests/report/labels_test.cpp).
struct SwatchLabels {
    std::string unseen;
    std::string not_compared;
    std::string nothing_behind = "no examined surface behind it";
    std::string examined_only = "examined surface only";
    std::string within_floor = "paler: within the floor";
    std::string region = "region, id as in regions.csv";
    std::string back_face = "dark: back of an open surface";
    std::string plane = "symmetry plane (its residual: report)";
};
[[nodiscard]] SwatchLabels swatch_labels(const LegendContent& content);
/// Where a swatch's label starts and its font size: 12 px margin, a 14 px swatch, 8 px gap (the
/// region's row 18 px more, for its tag).
inline constexpr int kSwatchLabelX = 34;
inline constexpr int kSwatchLabelFont = 13;

/// Smallest height that shows the bar, swatches and lines (regions are cut to what fits).
[[nodiscard]] int legend_min_height(const LegendContent& content);

/// Draws the legend into the panel at (x, y) of the given height.
void draw_legend(Canvas& dst, int x, int y, int height, const LegendContent& content);

/// A picture's canvas: the title line on top, the legend panel on the right; the picture
/// (picture_w × picture_h) goes at (0, kTitleHeight). An empty title leaves the title line
/// blank: draw_title() writes it into a copy (one legend drawn for many pictures).
[[nodiscard]] Canvas framed_sheet(int picture_w, int picture_h, const std::string& title,
                                  const LegendContent& legend);

/// The title line of a framed sheet.
void draw_title(Canvas& sheet, const std::string& title);

}  // namespace glint::detail
