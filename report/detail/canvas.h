// Drawing for glint's pictures on glint's canvas (image/canvas.h; private to report/): text in
// DejaVu Sans, the diverging colour map of the signed shape change, tags. Colour maps, lines,
// boxes and PNG encoding are OpenImageIO's, through the image plugin (image/image_ops.h); the
// text is FreeType's (report/detail/text.cpp: OIIO 2.4's render_text mangles UTF-8); only
// what OIIO lacks is written by hand elsewhere (shading, hatching, region contours:
// report/detail/surface_paint.h).
#pragma once

#include "image/canvas.h"
#include "image/image_ops.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint::detail {

/// How text lies against its anchor point.
enum class TextAlign { Left, Center, Right };

/// Colours of the pictures (linear values written as 8-bit PNG).
inline constexpr Rgb kBackground{0.125f, 0.135f, 0.155f};
inline constexpr Rgb kText{0.93f, 0.93f, 0.93f};
inline constexpr Rgb kDimText{0.68f, 0.70f, 0.74f};
inline constexpr Rgb kOutline{0.02f, 0.02f, 0.02f};
inline constexpr Rgb kUnseen{0.60f, 0.60f, 0.60f};
inline constexpr Rgb kUnseenStripe{0.30f, 0.30f, 0.30f};
/// Seen but not compared (decision/comparison.h): hatched the other way, warmer.
inline constexpr Rgb kNotCompared{0.80f, 0.78f, 0.70f};
inline constexpr Rgb kNotComparedStripe{0.48f, 0.45f, 0.38f};
/// A view's reference surface with no examined surface behind it (report/view_measurements.h):
/// violet hatching (no colour of the shape map is violet).
inline constexpr Rgb kNothingBehind{0.70f, 0.55f, 0.76f};
inline constexpr Rgb kNothingBehindStripe{0.42f, 0.28f, 0.48f};
/// Examined surface where the view's reference frame has none (beyond the reference outline):
/// green, so it is told from background and from the map's blue.
inline constexpr Rgb kExaminedOnly{0.30f, 0.78f, 0.42f};

/// The diverging map of signed shape change, low (loss, blue) → 0 (near white) → high
/// (gain, red): ColorBrewer's RdBu with 9 classes, reversed so blue is negative. 9 knots × 3
/// channels for ImageBufAlgo::color_map.
[[nodiscard]] std::span<const float> diverging_knots();

/// Colours `values` (one per pixel of a width × height image) on the diverging map with the
/// symmetric range [−limit, +limit] (values beyond are clamped; NaN maps to 0).
[[nodiscard]] Canvas diverging_image(const std::vector<float>& values, int width, int height,
                                     double limit);

/// The diverging map for per-pixel use: OpenImageIO's colours sampled when glint was built
/// (image/sampled_maps.h), so per-vertex and per-pixel colours need no image library and no
/// image per picture. The map is linear between its 9 knots, which fall on samples, so
/// interpolating the samples gives the map's own colours (to float rounding).
class DivergingTable {
  public:
    /// The table (static; thread-safe).
    [[nodiscard]] static const DivergingTable& get();
    /// The colour of `value` in the range ±limit (clamped; NaN maps to 0, as diverging_image).
    [[nodiscard]] Rgb operator()(float value, double limit) const;
    /// The colour at t ∈ [0, 1] of the map (clamped).
    [[nodiscard]] Rgb at(double t) const;
};

/// A width × height RGB image of 8 bits per channel (what the PNG pictures store: drawing,
/// copying and encoding need no conversion) filled with `colour`.
[[nodiscard]] Canvas canvas(int width, int height, Rgb colour = kBackground);

/// Whether the DejaVu font was found (text is decoration: without it pictures are unlabelled).
[[nodiscard]] bool has_font();

/// Whether the font draws `c` (not its missing-glyph box).
[[nodiscard]] bool font_has_glyph(char32_t c);

/// The code points of UTF-8 text; a byte that starts no valid sequence becomes U+FFFD.
[[nodiscard]] std::u32string decode_utf8(std::string_view text);

/// UTF-8 text ("°", "²", "−", "×", "±") with its baseline-left (or the alignment given) at
/// (x, y), drawn with FreeType (report/detail/text.cpp); `shadow` > 0 draws a dark halo of that
/// radius so the text reads on any colour. Text that does not fit the image whole is not drawn.
void draw_text(Canvas& dst, int x, int y, std::string_view text, int size, Rgb colour = kText,
               TextAlign align = TextAlign::Left, int shadow = 0);

/// Width in pixels of `text`'s ink at `size` (an estimate when no font is found).
[[nodiscard]] int text_width(std::string_view text, int size);

/// `text` if it is at most `max_width` pixels wide at `size`; else its longest start cut at a
/// space that fits with "…" appended (a parenthesis cut away whole), or "" when not even one
/// word fits.
[[nodiscard]] std::string fit_text(const std::string& text, int size, int max_width);

/// `text` on as many lines as it needs, each at most `max_width` px wide (the later ones at
/// most `next_width`): cut at a space, at " (" where that makes the first line fit. A word wider
/// than a line is cut with an ellipsis (fit_text), never left out.
[[nodiscard]] std::vector<std::string> wrap_text(const std::string& text, int size, int max_width,
                                                 int next_width);

/// A number on a small white tag with a dark border, centred on (x, y): the id of a region.
void draw_tag(Canvas& dst, int x, int y, std::string_view text, int size);

/// "%.3g"-style number with an explicit sign for non-zero values when `sign` is set; negative
/// numbers carry a minus sign (U+2212), not a hyphen.
/// (three significant digits, an exponent only below 1e-3-ish or from a million: 7890, not
/// 7.89e+03)
[[nodiscard]] std::string format_number(double value, bool sign = false);

/// A unit as pictures write it: "deg" as "°" (no space before it), others after a space.
[[nodiscard]] std::string picture_unit_suffix(std::string_view unit);

/// An angle in whole degrees with the degree sign: "30°", "+30°", "−15°".
[[nodiscard]] std::string format_degrees(double angle_deg, bool sign = false);

/// `text` with each hyphen that stands for minus (at the start, after a space, "(" or an
/// exponent's "e" after a digit) written as U+2212.
[[nodiscard]] std::string with_minus_sign(std::string text);

}  // namespace glint::detail
