// Where the pictures put region numbers (private to report/): beside their region, never on
// another number, a caption, an edge letter or the scale bar. A greedy placement, largest
// region first, over candidate spots around each region's box, further out ring by ring; a
// number that had to move away from its region is joined to it by a leader line.
#pragma once

#include "report/detail/canvas.h"
#include "report/detail/surface_paint.h"

#include <cstdint>
#include <string_view>
#include <vector>

namespace glint::detail {

/// A rectangle of pixels, [x0, x1) × [y0, y1).
struct PixelBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    [[nodiscard]] bool overlaps(const PixelBox& other) const {
        return x0 < other.x1 && other.x0 < x1 && y0 < other.y1 && other.y0 < y1;
    }
    [[nodiscard]] bool inside(int width, int height) const {
        return x0 >= 0 && y0 >= 0 && x1 <= width && y1 <= height;
    }
};

/// The box of a region's number tag (draw_tag) centred on (x, y).
[[nodiscard]] PixelBox tag_box(std::string_view text, int font_size, int x, int y);

/// The box text drawn by draw_text at (x, y) covers (ascent above the baseline, descent below).
[[nodiscard]] PixelBox text_box(std::string_view text, int font_size, int x, int y,
                                TextAlign align = TextAlign::Left);

struct PlacedLabel {
    std::int32_t id = 0;
    PixelBox box;      ///< the tag, picture pixels
    int anchor_x = 0;  ///< the region's anchor the leader line ends at
    int anchor_y = 0;
    bool has_leader = false;  ///< placed away from its region: a line joins them
};

/// Places the numbers of the anchors with at least `min_pixels` pixels in a width × height
/// picture, largest region first. Each takes the first candidate that lies inside the picture
/// and overlaps no number placed before and no `reserved` box; when none is free, it goes on
/// its anchor (as a last resort it may then cover something).
[[nodiscard]] std::vector<PlacedLabel> place_labels(const std::vector<RegionAnchor>& anchors,
                                                    int width, int height, int font_size,
                                                    std::size_t min_pixels,
                                                    const std::vector<PixelBox>& reserved);

/// Draws placed labels into a picture pasted at (x0, y0): leader lines first, then the tags.
void draw_labels(Canvas& dst, int x0, int y0, const std::vector<PlacedLabel>& labels,
                 int font_size);

/// Places (place_labels) and draws the numbers of a width × height picture pasted at (x0, y0),
/// keeping off `reserved` (picture pixels: captions, edge letters, the scale bar).
void draw_region_numbers(Canvas& dst, int x0, int y0, int width, int height,
                         const std::vector<RegionAnchor>& anchors, int font_size,
                         std::size_t min_pixels, const std::vector<PixelBox>& reserved = {});

}  // namespace glint::detail
