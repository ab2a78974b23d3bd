// The pictures' text (report/detail/text.cpp): UTF-8 decoded whole, and "°", "²", "³", "−",
// "×", "±" drawn with their own glyphs (OpenImageIO 2.4's render_text drew "°" as "0").
#include "report/detail/canvas.h"

#include <gtest/gtest.h>

#include <vector>

namespace glint {
namespace {

std::vector<float> drawn(std::string_view text) {
    Canvas c = detail::canvas(60, 48, {0.0f, 0.0f, 0.0f});
    detail::draw_text(c, 10, 36, text, 28, {1.0f, 1.0f, 1.0f});
    std::vector<float> px(60 * 48 * 3);
    for (std::size_t i = 0; i < px.size(); ++i) px[i] = static_cast<float>(c.pixels()[i]) / 255.0f;
    return px;
}

// The lowest row with ink, the pen's baseline at row 36.
int lowest_ink_row(const std::vector<float>& px) {
    int lowest = -1;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 60; ++x)
            if (px[static_cast<std::size_t>(3 * (y * 60 + x))] > 0.3f) lowest = y;
    return lowest;
}

TEST(Text, DecodesUtf8AndReplacesBrokenBytes) {
    EXPECT_EQ(detail::decode_utf8("a\u00b0\u00b2\u2212\u00d7"), U"a\u00b0\u00b2\u2212\u00d7");
    EXPECT_EQ(detail::decode_utf8("\U0001F600"), U"\U0001F600");
    EXPECT_EQ(detail::decode_utf8("x\xb0y"), U"x\uFFFDy");          // a lone continuation byte
    EXPECT_EQ(detail::decode_utf8("\xc2"), U"\uFFFD");              // cut short
    EXPECT_EQ(detail::decode_utf8("\xe2\x88z"), U"\uFFFD\uFFFDz");  // a broken sequence
}

TEST(Text, DrawsDegreeSuperscriptsMinusAndTimesWithTheirOwnGlyphs) {
    if (!detail::has_font()) GTEST_SKIP() << "DejaVu Sans not installed (fonts-dejavu-core)";
    for (const char32_t c : {U'\u00b0', U'\u00b2', U'\u00b3', U'\u2212', U'\u00d7', U'\u00b1'})
        EXPECT_TRUE(detail::font_has_glyph(c)) << static_cast<unsigned>(c);
    // A code point DejaVu Sans lacks: drawn as the missing-glyph box.
    ASSERT_FALSE(detail::font_has_glyph(U'\U0010FFFD'));
    const auto degree = drawn("\u00b0"), zero = drawn("0"), question = drawn("?"),
               missing = drawn("\U0010FFFD"), minus = drawn("\u2212"), hyphen = drawn("-");
    EXPECT_NE(degree, zero) << "the old bug: the low bits of the last byte, '0'";
    EXPECT_NE(degree, question);
    EXPECT_NE(degree, missing);
    EXPECT_NE(minus, hyphen);
    EXPECT_NE(minus, missing);
    // The degree sign sits high: its ink ends well above the baseline, where "0" reaches it.
    EXPECT_LT(lowest_ink_row(degree), 36 - 8);
    EXPECT_GE(lowest_ink_row(zero), 35);
    EXPECT_GT(detail::text_width("\u2212", 28), detail::text_width("-", 28))
        << "a minus is as wide as a plus, wider than a hyphen";
}

TEST(Text, NumbersAndAnglesCarryMinusAndDegreeSigns) {
    EXPECT_EQ(detail::format_number(-0.41, true), "\u22120.41");
    EXPECT_EQ(detail::format_number(0.41, true), "+0.41");
    EXPECT_EQ(detail::format_number(1.5e-5), "1.5e\u221205");
    EXPECT_EQ(detail::format_number(7893.4), "7890");
    EXPECT_EQ(detail::format_number(-23456.0, true), "\u221223500");
    EXPECT_EQ(detail::format_number(2.5e6), "2.5e+06");
    EXPECT_EQ(detail::format_degrees(-15.0, true), "\u221215\u00b0");
    EXPECT_EQ(detail::format_degrees(270.0), "270\u00b0");
    EXPECT_EQ(detail::with_minus_sign("one-sided (-3)"), "one-sided (\u22123)");
    EXPECT_EQ(detail::picture_unit_suffix("deg"), "\u00b0");
    EXPECT_EQ(detail::picture_unit_suffix("mm"), " mm");
}

}  // namespace
}  // namespace glint
