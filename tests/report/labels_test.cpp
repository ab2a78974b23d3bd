// Region numbers placed without collisions (report/detail/labels.h): off each other, off
// captions, edge letters and the scale bar, inside the picture, with a leader line when moved.
#include "report/detail/labels.h"
#include "report/detail/canvas.h"
#include "report/detail/legend.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

detail::RegionAnchor anchor(std::int32_t id, int x, int y, int half, std::size_t pixels) {
    return {.id = id,
            .x = x,
            .y = y,
            .pixels = pixels,
            .min_x = x - half,
            .min_y = y - half,
            .max_x = x + half,
            .max_y = y + half};
}

// Three small regions side by side and one more below them: each one's first choice (right of
// its box) is where its neighbour's number or region is, and a caption covers the spot right
// of the third.
TEST(Labels, CollidingNumbersAreSpreadOffEachOtherAndOffReservedBoxes) {
    const std::vector<detail::RegionAnchor> anchors{
        anchor(1, 100, 100, 4, 90), anchor(2, 112, 100, 4, 80), anchor(3, 124, 100, 4, 70),
        anchor(4, 112, 110, 4, 60), anchor(5, 300, 300, 2, 3)};  // 5: too small to number
    const detail::PixelBox caption{130, 90, 240, 112};
    const std::vector<detail::PixelBox> reserved{caption};
    const auto placed = detail::place_labels(anchors, 320, 320, 13, 20, reserved);
    ASSERT_EQ(placed.size(), 4u);
    EXPECT_EQ(placed[0].id, 1) << "largest region first";
    for (std::size_t i = 0; i < placed.size(); ++i) {
        EXPECT_TRUE(placed[i].box.inside(320, 320)) << placed[i].id;
        EXPECT_FALSE(placed[i].box.overlaps(caption)) << placed[i].id;
        for (std::size_t j = i + 1; j < placed.size(); ++j)
            EXPECT_FALSE(placed[i].box.overlaps(placed[j].box))
                << placed[i].id << " and " << placed[j].id;
    }
}

// Everything beside the region is taken (a caption around it): its number moves further out
// and a leader line joins it to the region's anchor.
TEST(Labels, ANumberMovedAwayGetsALeaderToItsRegion) {
    const detail::PixelBox around{60, 60, 140, 140};
    const auto placed =
        detail::place_labels({anchor(3, 100, 100, 4, 90)}, 320, 320, 13, 20, {around});
    ASSERT_EQ(placed.size(), 1u);
    EXPECT_FALSE(placed[0].box.overlaps(around));
    EXPECT_TRUE(placed[0].has_leader);
    EXPECT_EQ(placed[0].anchor_x, 100);
    EXPECT_EQ(placed[0].anchor_y, 100);
    // The nearest free ring: within a few tag heights of the blocked box.
    EXPECT_LT(std::max(placed[0].box.x0 - around.x1, around.x0 - placed[0].box.x1), 40);
}

TEST(Labels, ANumberNearTheEdgeStaysInsideThePicture) {
    const auto placed = detail::place_labels({anchor(7, 3, 3, 2, 50), anchor(8, 316, 316, 2, 50)},
                                             320, 320, 13, 20, {});
    ASSERT_EQ(placed.size(), 2u);
    for (const auto& l : placed) EXPECT_TRUE(l.box.inside(320, 320)) << l.id;
    EXPECT_FALSE(placed[0].has_leader);
}

TEST(Labels, TextBoxesCoverWhatIsDrawn) {
    const auto left = detail::text_box("from anterior", 13, 8, 300);
    EXPECT_LE(left.x0, 8);
    EXPECT_GE(left.x1, 8 + detail::text_width("from anterior", 13));
    EXPECT_LE(left.y0, 300 - 10);
    EXPECT_GE(left.y1, 300);
    const auto right = detail::text_box("R", 13, 314, 165, detail::TextAlign::Right);
    EXPECT_GE(right.x1, 314);
    EXPECT_LE(right.x0, 314 - detail::text_width("R", 13));
}

TEST(Text, TitlesTooWideAreCutAtAWordWithAnEllipsis) {
    const std::string title = "from anterior-superior-left (az 270\u00b0, el +30\u00b0)";
    EXPECT_EQ(detail::fit_text(title, 13, 2000), title);
    const std::string cut = detail::fit_text(title, 13, detail::text_width(title, 13) - 5);
    EXPECT_EQ(cut, "from anterior-superior-left\u2026") << "the parenthesis goes whole";
    EXPECT_LE(detail::text_width(cut, 13), detail::text_width(title, 13) - 5);
    EXPECT_EQ(detail::fit_text(title, 13, 5), "");
}

// A legend note wider than the panel goes on as many lines as it needs, each within its width,
// every word kept (it used to be left out whole when its parenthesis alone did not fit).
TEST(Text, NotesTooWideWrapOnAsManyLinesAsTheyNeedAndLoseNoWord) {
    const std::string note =
        "not compared (border, unscanned, thin): hatched in the views and grey on the atlas, "
        "counted in no cell of the chart (report.json comparison.not_compared)";
    const int width = 270;
    const int next = 260;
    const auto lines = detail::wrap_text(note, 12, width, next);
    ASSERT_GE(lines.size(), 3u);
    std::string joined;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        EXPECT_LE(detail::text_width(lines[i], 12), i == 0 ? width : next) << lines[i];
        joined += (i ? " " : "") + lines[i];
    }
    EXPECT_EQ(joined, note);
    EXPECT_EQ(detail::wrap_text("short", 12, width, next), std::vector<std::string>{"short"});
    // The parenthesis goes to the next line whole where that makes the first fit.
    const std::string range = "range \u00b13.5 mm (the 99th percentile of |shape change|)";
    const auto two =
        detail::wrap_text(range, 12, detail::text_width("range \u00b13.5 mm", 12) + 4, 1000);
    ASSERT_EQ(two.size(), 2u);
    EXPECT_EQ(two[0], "range \u00b13.5 mm");
    // A single word wider than the line is cut with an ellipsis, whole UTF-8 characters only.
    const auto word = detail::wrap_text("\u00b1\u00b1\u00b1\u00b1\u00b1\u00b1\u00b1\u00b1", 12,
                                        detail::text_width("\u00b1\u00b1\u00b1", 12) + 12, 40);
    ASSERT_EQ(word.size(), 1u);
    EXPECT_NE(word[0].find("\u2026"), std::string::npos);
    EXPECT_EQ(word[0].rfind("\u00b1", 0), 0u);
    EXPECT_EQ((word[0].size() - std::string("\u2026").size()) % std::string("\u00b1").size(), 0u);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// Issue 51: the legend's "not compared (border, unscanned, thin)" ran past the panel and showed
// as "…thin" cut at the edge. Every swatch label, in every legend, fits the panel.
TEST(Legend, EverySwatchLabelFitsThePanel) {
    for (const bool measured : {false, true})
        for (const bool roi : {false, true}) {
            detail::LegendContent c;
            c.measured = measured;
            c.roi = roi;
            const detail::SwatchLabels l = detail::swatch_labels(c);
            for (const std::string& text :
                 {l.unseen, l.not_compared, l.nothing_behind, l.examined_only, l.within_floor,
                  l.back_face, l.plane}) {
                const int right =
                    detail::kSwatchLabelX + detail::text_width(text, detail::kSwatchLabelFont);
                EXPECT_LE(right, detail::kLegendWidth - 4) << '"' << text << '"';
            }
            const int region =
                detail::kSwatchLabelX + 18 + detail::text_width(l.region, detail::kSwatchLabelFont);
            EXPECT_LE(region, detail::kLegendWidth - 4) << l.region;
        }
}

}  // namespace
}  // namespace glint
