#include "report/detail/legend.h"

#include "report/detail/surface_paint.h"
#include "report/detail/symmetry_plane_trace.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace glint::detail {

namespace {

constexpr int kLegendFont = 13;
constexpr int kLegendLine = 18;  // px per text line
constexpr int kBarWidth = 20;
constexpr int kMinBar = 120;
constexpr int kMaxBar = 260;
constexpr int kSwatchStep = kLegendLine + 6;  // px from one swatch row to the next

// Height of the swatch rows: four; six for a view's own measurement.
int swatches_height(const LegendContent& c) {
    return ((c.measured ? 6 : 4) + (c.plane_line ? 1 : 0)) * kSwatchStep - 4;
}

// The bar, high values at the top: pixel row of value v.
int bar_row(double v, double limit, int top, int height) {
    const double t = std::clamp(0.5 - 0.5 * v / limit, 0.0, 1.0);
    return top + static_cast<int>(std::lround(t * (height - 1)));
}

void draw_bar(Canvas& dst, int x, int top, int height, const LegendContent& c) {
    std::vector<float> ramp(static_cast<std::size_t>(height) * kBarWidth);
    for (int y = 0; y < height; ++y)
        for (int i = 0; i < kBarWidth; ++i)
            ramp[static_cast<std::size_t>(y * kBarWidth + i)] =
                static_cast<float>(c.limit * (1.0 - 2.0 * y / std::max(1, height - 1)));
    dst.paste(diverging_image(ramp, kBarWidth, height, c.limit), x, top);
    draw_box(dst, x - 1, top - 1, x + kBarWidth, top + height, kDimText, false);
    const std::string unit = " " + c.unit;
    for (int k = -2; k <= 2; ++k) {
        const double v = c.limit * k / 2.0;
        const int row = bar_row(v, c.limit, top, height);
        draw_line(dst, x + kBarWidth, row, x + kBarWidth + 5, row, kText);
        draw_text(dst, x + kBarWidth + 9, row + kLegendFont / 2 - 1,
                  format_number(v, true) + (k == 2 ? unit : ""), kLegendFont);
    }
    if (c.shape_floor > 0 && c.shape_floor < c.limit) {
        // The shape floor: below it a change is not told apart from tessellation and noise.
        for (double v : {c.shape_floor, -c.shape_floor}) {
            const int row = bar_row(v, c.limit, top, height);
            draw_line(dst, x - 4, row, x + kBarWidth - 1, row, kOutline);
        }
    }
}

// A swatch hatched as the pictures hatch: rising stripes (or falling) every 7 px.
void hatched_swatch(Canvas& dst, int x, int y, Rgb plain, Rgb stripe, bool rising) {
    const int s = kLegendLine - 4;
    for (int j = 0; j < s; ++j)
        for (int i = 0; i < s; ++i) {
            const bool on = rising ? (i + j) % 7 < 2 : (i + 7 * s - j) % 7 < 2;
            if (x + i < dst.width() && y + j < dst.height())
                dst.set(x + i, y + j, on ? stripe : plain);
        }
}

// The rows of a view's own measurement: nothing behind, examined only, pale within the floor.
int draw_measured_swatches(Canvas& dst, int x, int y, const LegendContent& c) {
    const int s = kLegendLine - 4;
    const SwatchLabels labels = swatch_labels(c);
    hatched_swatch(dst, x, y, kNothingBehind, kNothingBehindStripe, true);
    draw_text(dst, x + s + 8, y + s - 2, labels.nothing_behind, kLegendFont);
    y += kSwatchStep;
    draw_box(dst, x, y, x + s, y + s, kExaminedOnly, true);
    draw_text(dst, x + s + 8, y + s - 2, labels.examined_only, kLegendFont);
    y += kSwatchStep;
    const DivergingTable& colours = DivergingTable::get();
    const Rgb loss = colours(static_cast<float>(-c.limit), c.limit);
    const Rgb white = colours(0.0f, c.limit);
    Rgb pale = loss;
    for (int k = 0; k < 3; ++k) pale[k] += kWithinFloorPale * (white[k] - pale[k]);
    draw_box(dst, x, y, x + s / 2, y + s, loss, true);
    draw_box(dst, x + s / 2 + 1, y, x + s, y + s, pale, true);
    draw_text(dst, x + s + 8, y + s - 2, labels.within_floor, kLegendFont);
    return y + kSwatchStep;
}

void draw_swatches(Canvas& dst, int x, int y, const LegendContent& c) {
    const int s = kLegendLine - 4;
    const SwatchLabels labels = swatch_labels(c);
    if (c.measured) {
        y = draw_measured_swatches(dst, x, y, c);
    } else {
        // Unseen: the hatching the pictures use.
        hatched_swatch(dst, x, y, kUnseen, kUnseenStripe, true);
        draw_text(dst, x + s + 8, y + s - 2, labels.unseen, kLegendFont);
        y += kSwatchStep;
    }
    // Not compared: hatched the other way.
    hatched_swatch(dst, x, y, kNotCompared, kNotComparedStripe, false);
    draw_text(dst, x + s + 8, y + s - 2, labels.not_compared, kLegendFont);
    const int y2 = y + kSwatchStep;
    draw_box(dst, x, y2, x + s, y2 + s, {0.97f, 0.97f, 0.97f}, true);
    draw_box(dst, x, y2, x + s, y2 + s, kOutline, false);
    draw_box(dst, x + 1, y2 + 1, x + s - 1, y2 + s - 1, kOutline, false);
    draw_tag(dst, x + s + 14, y2 + s / 2, "1", kLegendFont - 2);
    draw_text(dst, x + s + 26, y2 + s - 2, labels.region, kLegendFont);
    // An open surface seen from behind: its normals face away, so the light leaves it dark.
    const int y3 = y2 + kSwatchStep;
    draw_box(dst, x, y3, x + s, y3 + s, back_face_colour(), true);
    draw_text(dst, x + s + 8, y3 + s - 2, labels.back_face, kLegendFont);
    if (!c.plane_line) return;
    const int y4 = y3 + kSwatchStep;
    draw_box(dst, x, y4 + s / 2 - 1, x + s, y4 + s / 2, kSymmetryPlane, true);
    draw_text(dst, x + s + 8, y4 + s - 2, labels.plane, kLegendFont);
}

}  // namespace

SwatchLabels swatch_labels(const LegendContent& c) {
    SwatchLabels l;
    l.unseen = c.roi ? "unseen, or outside the ROI" : "unseen (no view saw it)";
    // note: "not compared (border, unscanned, thin)" ran past the panel's edge at 13 px
    // (issue 51: the legend's "thin)" was cut); the kinds are named in the report's text.
    l.not_compared = c.measured ? "not compared (edge, border)" : "not compared (edge, gap, thin)";
    return l;
}

std::string region_kind_name(const Region& r, bool mirror) {
    if (!mirror) return r.is_hole_loss() ? "surface gone" : to_string(r.kind);
    switch (r.kind) {
        case RegionKind::Dent: return "less";
        case RegionKind::Bump: return "more";
        case RegionKind::MissingSurface: break;
    }
    return "no mirrored surface";
}

std::string region_legend_line(const Region& r, const std::string& unit, bool mirror) {
    const std::string area = format_number(r.area) + " " + unit + "\u00b2";
    if (r.kind == RegionKind::MissingSurface)
        return std::to_string(r.id) + "  " + region_kind_name(r, mirror) + ", " + area;
    return std::to_string(r.id) + "  " + region_kind_name(r, mirror) + "  " +
           format_number(r.peak_depth, true) + " " + unit + ", " + area;
}

namespace {

// The legend's notes as drawn: the range and the shape floor first, then c.lines, each on as
// many lines as the panel's width needs (continuations indented).
struct NoteLine {
    std::string text;
    bool continued = false;
};

std::vector<NoteLine> note_lines(const LegendContent& c) {
    std::vector<std::string> lines = c.lines;
    lines.insert(lines.begin(), "range \u00b1" + format_number(c.limit) + " " + c.unit +
                                    (c.limit_source.empty() ? "" : " (" + c.limit_source + ")"));
    if (c.shape_floor > 0)
        lines.insert(lines.begin() + 1,
                     "shape floor \u00b1" + format_number(c.shape_floor) + " " + c.unit +
                         (c.shape_floor < c.limit ? " (marked on the bar)" : ""));
    std::vector<NoteLine> out;
    for (const auto& l : lines) {
        const auto parts = wrap_text(l, kLegendFont - 1, kLegendWidth - 20, kLegendWidth - 30);
        for (std::size_t i = 0; i < parts.size(); ++i) out.push_back({parts[i], i > 0});
    }
    return out;
}

}  // namespace

int legend_min_height(const LegendContent& c) {
    return 10 + 2 * kLegendLine + kMinBar + kLegendLine + 12 + swatches_height(c) +
           static_cast<int>(note_lines(c).size()) * kLegendLine + 2 * kLegendLine + 10;
}

void draw_legend(Canvas& dst, int x, int y, int height, const LegendContent& c) {
    const int x0 = x + 12;
    int cy = y + 10 + kLegendFont;
    const std::string what = c.measured ? "signed depth, this view ("
                             : c.mirror ? "this side − mirrored other ("
                                        : "signed shape change (";
    draw_text(dst, x0, cy, what + c.unit + ")", kLegendFont + 1);
    cy += kLegendLine;
    draw_text(dst, x0, cy, c.mirror ? "more than the mirrored other side (bump)" : "gain (bump)",
              kLegendFont, {0.94f, 0.55f, 0.50f});
    cy += 8;
    const int fixed = legend_min_height(c) - kMinBar;
    const int bar = std::clamp(height - fixed - static_cast<int>(c.regions.size()) * kLegendLine,
                               kMinBar, kMaxBar);
    draw_bar(dst, x0 + 4, cy, bar, c);
    cy += bar + kLegendLine;
    draw_text(dst, x0, cy, c.mirror ? "less than the mirrored other side (dent)" : "loss (dent)",
              kLegendFont, {0.55f, 0.72f, 0.95f});
    cy += 12;
    draw_swatches(dst, x0, cy, c);
    cy += swatches_height(c) + kLegendLine;
    // A note too wide for the panel goes on as many lines as it needs (never left out).
    for (const auto& l : note_lines(c)) {
        draw_text(dst, l.continued ? x0 + 10 : x0, cy, l.text, kLegendFont - 1, kDimText);
        cy += kLegendLine - 2;
    }
    if (c.regions.empty()) {
        draw_text(dst, x0, cy + 4, "no region", kLegendFont);
        return;
    }
    cy += 4;
    for (std::size_t i = 0; i < c.regions.size(); ++i) {
        if (cy + 2 * kLegendLine > y + height && i + 1 < c.regions.size()) {
            // Regions come largest first: what is cut is the smaller ones, listed in full
            // where there is room for them.
            draw_text(dst, x0, cy,
                      "+ " + std::to_string(c.regions.size() - i) +
                          " smaller: all in report.html, regions.csv",
                      kLegendFont - 1);
            break;
        }
        draw_text(dst, x0, cy, c.regions[i], kLegendFont - 1);
        cy += kLegendLine - 1;
    }
}

Canvas framed_sheet(int picture_w, int picture_h, const std::string& title,
                    const LegendContent& legend) {
    const int h = kTitleHeight + std::max(picture_h, legend_min_height(legend));
    Canvas sheet = canvas(picture_w + kLegendWidth, h);
    draw_title(sheet, title);
    draw_legend(sheet, picture_w, kTitleHeight, h - kTitleHeight, legend);
    return sheet;
}

void draw_title(Canvas& sheet, const std::string& title) { draw_text(sheet, 8, 20, title, 15); }

}  // namespace glint::detail
