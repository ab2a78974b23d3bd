#include "report/detail/view_chart.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glint::detail {

namespace {

constexpr int kLeft = 64;    // px: row labels
constexpr int kTop = 24;     // px: the row title above the grid
constexpr int kBottom = 92;  // px: column labels, column title, colour key
constexpr int kKeyWidth = 220;
constexpr int kMinWidth = 440;  // px: the key's caption fits
constexpr int kChartFont = 12;

// viridis at 256 + 1 evenly spaced points of [0, 1], from ImageBufAlgo::color_map.
const std::vector<Rgb>& viridis_table() {
    static const std::vector<Rgb> table = [] {
        constexpr int n = 257;
        std::vector<float> ramp(n);
        for (int i = 0; i < n; ++i)
            ramp[static_cast<std::size_t>(i)] = static_cast<float>(i) / (n - 1);
        const std::vector<float> mapped = color_map(ramp, "viridis");
        std::vector<Rgb> t(n);
        for (std::size_t i = 0; i < t.size(); ++i)
            t[i] = {mapped[3 * i], mapped[3 * i + 1], mapped[3 * i + 2]};
        return t;
    }();
    return table;
}

std::string percent(double share) {
    char b[32];
    const double p = 100.0 * share;
    std::snprintf(b, sizeof b, p == 0 ? "0" : p < 10 ? "%.1f" : "%.0f", p);
    return std::string(b) + " %";
}

std::string joined_ids(const std::vector<std::int32_t>& ids) {
    std::string s;
    for (std::size_t i = 0; i < ids.size() && i < 3; ++i)
        s += (i ? "," : "") + std::to_string(ids[i]);
    return ids.size() > 3 ? s + "…" : s;
}

void draw_cell(Canvas& img, int x, int y, const ChartCell& cell, double top) {
    const int w = kChartCellWidth - 2, h = kChartCellHeight - 2;
    if (!cell.measured) {
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i)
                img.set(x + i, y + j, (i + j) % 7 < 2 ? kUnseenStripe : kUnseen);
        draw_text(img, x + w / 2, y + h / 2 + 4, "n/a", kChartFont - 1, kOutline,
                  TextAlign::Center);
        return;
    }
    const Rgb c = chart_colour(cell.share, top);
    draw_box(img, x, y, x + w - 1, y + h - 1, c, true);
    const float luminance = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
    draw_text(img, x + w / 2, y + h - 6, percent(cell.share), kChartFont - 1,
              luminance > 0.45f ? kOutline : kText, TextAlign::Center);
    if (cell.best_of.empty()) return;
    // A region's best view: framed in white, the regions' ids on a tag.
    draw_box(img, x, y, x + w - 1, y + h - 1, {1, 1, 1}, false);
    draw_box(img, x + 1, y + 1, x + w - 2, y + h - 2, {1, 1, 1}, false);
    draw_tag(img, x + w / 2, y + 10, joined_ids(cell.best_of), kChartFont - 2);
}

void draw_key(Canvas& img, int x, int y, double top) {
    for (int i = 0; i < kKeyWidth; ++i) {
        const Rgb c = chart_colour(top * i / (kKeyWidth - 1), top);
        draw_box(img, x + i, y, x + i, y + 9, c, true);
    }
    draw_text(img, x - 6, y + 10, "0 %", kChartFont, kText, TextAlign::Right);
    draw_text(img, x + kKeyWidth + 6, y + 10, percent(top), kChartFont);
    draw_text(img, x, y + 28, "share of the view's compared pixels beyond the floor", kChartFont,
              kDimText);
}

}  // namespace

Rgb chart_colour(double share, double top) {
    const auto& t = viridis_table();
    const double u =
        std::clamp(top > 0 ? share / top : 0.0, 0.0, 1.0) * static_cast<double>(t.size() - 1);
    const auto i = std::min(static_cast<std::size_t>(u), t.size() - 2);
    const auto f = static_cast<float>(u - static_cast<double>(i));
    Rgb c{};
    for (int k = 0; k < 3; ++k) c[k] = t[i][k] + f * (t[i + 1][k] - t[i][k]);
    return c;
}

std::array<int, 2> chart_cell_origin(int column, int row) {
    return {kLeft + column * kChartCellWidth + 1, kTop + row * kChartCellHeight + 1};
}

double chart_top(const std::vector<ChartCell>& cells) {
    double largest = 0.0;
    for (const auto& c : cells)
        if (c.measured) largest = std::max(largest, c.share);
    // note: 1 %: a sweep that measured almost nothing beyond its floor keeps a dark chart
    // instead of stretching a few stray pixels to full colour.
    const double x = std::max(largest, 0.01);
    const double e = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * e >= x * (1 - 1e-9)) return std::min(1.0, m * e);
    return 1.0;
}

Canvas view_chart(const ChartInput& in) {
    const int cols = std::max<int>(1, static_cast<int>(in.column_labels.size()));
    const int rows = std::max<int>(1, static_cast<int>(in.row_labels.size()));
    const int grid_w = cols * kChartCellWidth, grid_h = rows * kChartCellHeight;
    const int width = std::max(kMinWidth, kLeft + grid_w + 12);
    Canvas img = canvas(width, kTop + grid_h + kBottom);
    const double top = chart_top(in.cells);
    draw_text(img, kLeft - 6, kTop - 8, in.row_title, kChartFont, kDimText, TextAlign::Right);
    for (int r = 0; r < rows; ++r)
        draw_text(img, kLeft - 6, kTop + r * kChartCellHeight + kChartCellHeight / 2 + 4,
                  in.row_labels[static_cast<std::size_t>(r)], kChartFont, kText, TextAlign::Right);
    for (int c = 0; c < cols; ++c)
        draw_text(img, kLeft + c * kChartCellWidth + kChartCellWidth / 2, kTop + grid_h + 14,
                  in.column_labels[static_cast<std::size_t>(c)], kChartFont, kText,
                  TextAlign::Center);
    draw_text(img, kLeft + grid_w / 2, kTop + grid_h + 32, in.column_title, kChartFont, kDimText,
              TextAlign::Center);
    for (const auto& cell : in.cells)
        if (cell.column >= 0 && cell.column < cols && cell.row >= 0 && cell.row < rows) {
            const auto [x, y] = chart_cell_origin(cell.column, cell.row);
            draw_cell(img, x, y, cell, top);
        }
    draw_key(img, kLeft + 30, kTop + grid_h + 46, top);
    return img;
}

}  // namespace glint::detail
