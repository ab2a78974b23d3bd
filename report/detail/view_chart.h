// The mosaic's summary chart (private to report/): one cell per view of a zoom, azimuth across
// and elevation down for a rotary sweep (a sphere sweep's views in plan order), coloured by how
// much of what the view compared it measured beyond the zoom's floor (viridis, 0 to the largest
// share rounded up; the share printed in the cell), the regions' best views framed in white
// with the regions' ids, views with no measurement (a GPU sweep) hatched. Axes are labelled in
// degrees, a colour key below names the quantity.
#pragma once

#include "report/detail/canvas.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace glint::detail {

struct ChartCell {
    int column = 0;
    int row = 0;
    bool measured = false;              ///< false: no per-view pixels came back (drawn hatched)
    double share = 0.0;                 ///< of the compared pixels beyond the floor, 0…1
    std::vector<std::int32_t> best_of;  ///< regions whose best view this is
};

struct ChartInput {
    std::vector<std::string> column_labels;  ///< one per column ("0°", "30°" …)
    std::vector<std::string> row_labels;     ///< one per row ("+60°" …)
    std::string column_title;                ///< "azimuth"
    std::string row_title;                   ///< "elevation"
    std::vector<ChartCell> cells;
};

/// Cell size of the chart, pixels.
inline constexpr int kChartCellWidth = 56;
inline constexpr int kChartCellHeight = 34;

/// Pixel of the chart image where the cell of (column, row) begins (its top-left corner; the
/// cell's colour fills kChartCellWidth − 2 × kChartCellHeight − 2 pixels from there).
[[nodiscard]] std::array<int, 2> chart_cell_origin(int column, int row);

/// The chart as an 8-bit RGB image on the pictures' background.
[[nodiscard]] Canvas view_chart(const ChartInput& input);

/// The colour of a share of `top` on the chart's map (viridis; clamped).
[[nodiscard]] Rgb chart_colour(double share, double top);

/// The chart's top share: the largest cell's rounded up to 1, 2 or 5 × 10^k (at least 1 %).
[[nodiscard]] double chart_top(const std::vector<ChartCell>& cells);

}  // namespace glint::detail
