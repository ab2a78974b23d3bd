#include "report/detail/scale_bar.h"

#include <algorithm>
#include <cmath>

namespace glint::detail {

namespace {

constexpr int kScaleLabelFont = 12;
constexpr int kMargin = 10;  // px from the picture's right and bottom edges

}  // namespace

double round_length_at_most(double x) {
    const double decade = std::pow(10.0, std::floor(std::log10(x)));
    // note: the tolerance keeps an exact 2 or 5 × 10^k (log10 rounds) at its own value.
    for (const double m : {5.0, 2.0, 1.0})
        if (m * decade <= x * (1 + 1e-9)) return m * decade;
    return decade / 2.0;
}

std::string scale_bar_label(double length, const std::string& unit, bool perspective) {
    return format_number(length) + " " + unit + (perspective ? " at front" : "");
}

double picture_units_per_px(const View& view) {
    return view.camera.projection == Projection::Orthographic ? view.camera.footprint_at(0.0)
                                                              : view.footprint;
}

ScaleBar scale_bar(double units_per_px, int max_pixels, const std::string& unit, bool perspective) {
    ScaleBar bar;
    if (!(units_per_px > 0) || !std::isfinite(units_per_px) || max_pixels < 1) return bar;
    bar.length = round_length_at_most(units_per_px * max_pixels);
    bar.pixels = static_cast<int>(std::lround(bar.length / units_per_px));
    bar.label = scale_bar_label(bar.length, unit, perspective);
    return bar;
}

ScaleBar view_scale_bar(const View& view, const std::string& unit) {
    return scale_bar(picture_units_per_px(view), view.camera.width / 4, unit,
                     view.camera.projection == Projection::Perspective);
}

void draw_scale_bar(Canvas& dst, int right, int bottom, const ScaleBar& bar) {
    if (bar.pixels < 1) return;
    const int left = right - bar.pixels + 1;
    const int top = bottom - kScaleBarThickness + 1;
    // A dark border so the bar reads on white (no change) and on the background alike.
    draw_box(dst, left - 1, top - 1, right + 1, bottom + 1, kOutline, true);
    draw_box(dst, left, top, right, bottom, kScaleBarColour, true);
    draw_text(dst, right, top - 5, bar.label, kScaleLabelFont, kText, TextAlign::Right, 2);
}

PixelBox view_scale_bar_box(const View& view, const std::string& unit) {
    const ScaleBar bar = view_scale_bar(view, unit);
    if (bar.pixels < 1) return {};
    const int right = view.camera.width - kMargin, bottom = view.camera.height - kMargin;
    const int top = bottom - kScaleBarThickness + 1;
    const int left = right - std::max(bar.pixels, text_width(bar.label, kScaleLabelFont));
    return {left - 3, top - 5 - kScaleLabelFont - 3, right + 3, bottom + 3};
}

void draw_view_scale_bar(Canvas& dst, int x0, int y0, const View& view, const std::string& unit) {
    draw_scale_bar(dst, x0 + view.camera.width - kMargin, y0 + view.camera.height - kMargin,
                   view_scale_bar(view, unit));
}

}  // namespace glint::detail
