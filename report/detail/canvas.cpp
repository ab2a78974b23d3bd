#include "report/detail/canvas.h"

#include "image/diverging_knots.h"
#include "image/sampled_maps.h"
#include "mesh/error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <utility>

namespace glint::detail {

std::span<const float> diverging_knots() { return kDivergingKnots; }

Canvas diverging_image(const std::vector<float>& values, int width, int height, double limit) {
    GLINT_ASSERT(
        values.size() == static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
        "diverging image: size does not match its values");
    GLINT_ASSERT(limit > 0, "diverging image: the range must be positive");
    std::vector<float> t(values.size());
    for (std::size_t i = 0; i < t.size(); ++i) {
        const float v = values[i];
        t[i] =
            std::isnan(v) ? 0.5f : static_cast<float>(std::clamp(0.5 + 0.5 * v / limit, 0.0, 1.0));
    }
    const std::vector<float> rgb = color_map(t, kDivergingKnots);
    std::vector<std::uint8_t> bytes(rgb.size());
    std::transform(rgb.begin(), rgb.end(), bytes.begin(), to_byte);
    return Canvas(width, height, 3, std::move(bytes));
}

const DivergingTable& DivergingTable::get() {
    static const DivergingTable table;
    return table;
}

Rgb DivergingTable::operator()(float value, double limit) const {
    return at(std::isnan(value)
                  ? 0.5
                  : std::clamp(0.5 + 0.5 * static_cast<double>(value) / limit, 0.0, 1.0));
}

Rgb DivergingTable::at(double t) const { return sampled_colour(SampledMap::Diverging, t); }

Canvas canvas(int width, int height, Rgb colour) { return Canvas(width, height, 3, colour); }

void draw_tag(Canvas& dst, int x, int y, std::string_view text, int size) {
    const int w = text_width(text, size) + size / 2 + 2;
    const int h = size + size / 4 + 2;
    const int x0 = x - w / 2, y0 = y - h / 2;
    draw_box(dst, x0, y0, x0 + w, y0 + h, Rgb{1.0f, 1.0f, 1.0f}, true);
    draw_box(dst, x0, y0, x0 + w, y0 + h, kOutline, false);
    // note: the baseline sits a fifth of the size above the box's bottom edge (DejaVu's
    // descent), so digits look centred.
    draw_text(dst, x, y0 + h - 1 - size / 5 - 1, text, size, {0.0f, 0.0f, 0.0f}, TextAlign::Center);
}

std::string format_number(double value, bool sign) {
    char buf[48];
    const double shown = std::abs(value) < 5e-13 ? 0.0 : value;
    if (std::abs(shown) >= 1000.0 && std::abs(shown) < 1e6) {
        // three significant digits without an exponent: 7890, not 7.89e+03
        const double step = std::pow(10.0, std::floor(std::log10(std::abs(shown))) - 2.0);
        std::snprintf(buf, sizeof buf, sign ? "%+.0f" : "%.0f", std::round(shown / step) * step);
    } else {
        std::snprintf(buf, sizeof buf, sign && shown != 0.0 ? "%+.3g" : "%.3g", shown);
    }
    return with_minus_sign(buf);
}

std::string with_minus_sign(std::string text) {
    // U+2212 MINUS SIGN: a hyphen reads as a dash next to a word.
    for (std::size_t at = text.find('-'); at != std::string::npos; at = text.find('-', at + 3))
        if (at == 0 || text[at - 1] == ' ' || text[at - 1] == '(' ||
            (at >= 2 && text[at - 1] == 'e' &&
             std::isdigit(static_cast<unsigned char>(text[at - 2]))))
            text.replace(at, 1, "\u2212");
    return text;
}

std::string picture_unit_suffix(std::string_view unit) {
    if (unit == "deg") return "\u00b0";
    return unit.empty() ? std::string() : " " + std::string(unit);
}

std::string format_degrees(double angle_deg, bool sign) {
    char buf[48];
    const double shown = std::abs(angle_deg) < 0.5 ? 0.0 : angle_deg;
    std::snprintf(buf, sizeof buf, sign ? "%+.0f\u00b0" : "%.0f\u00b0", shown);
    return with_minus_sign(buf);
}

}  // namespace glint::detail
