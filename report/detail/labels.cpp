#include "report/detail/labels.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace glint::detail {

namespace {

constexpr int kRings = 8;  // candidate rings around a region before giving up

// Candidate centres for a tag of w × h around the anchor's box, nearest first: beside the box
// (right, left, above, below, at the anchor's row or column), then the corners, each ring one
// tag height further out.
std::vector<std::pair<int, int>> candidates(const RegionAnchor& a, int w, int h) {
    std::vector<std::pair<int, int>> out;
    const int gap = 3;
    for (int ring = 0; ring < kRings; ++ring) {
        const int d = ring * h;
        const int right = a.max_x + gap + w / 2 + 1 + d, left = a.min_x - gap - w / 2 - 1 - d;
        const int above = a.min_y - gap - h / 2 - 1 - d, below = a.max_y + gap + h / 2 + 1 + d;
        for (const int shift : {0, -h, h}) {
            out.emplace_back(right, a.y + shift);
            out.emplace_back(left, a.y + shift);
            out.emplace_back(a.x + shift * w / h, above);
            out.emplace_back(a.x + shift * w / h, below);
        }
        out.emplace_back(right, above);
        out.emplace_back(left, above);
        out.emplace_back(right, below);
        out.emplace_back(left, below);
    }
    return out;
}

bool is_free(const PixelBox& box, int width, int height, const std::vector<PixelBox>& taken) {
    if (!box.inside(width, height)) return false;
    return std::none_of(taken.begin(), taken.end(),
                        [&](const PixelBox& t) { return box.overlaps(t); });
}

}  // namespace

PixelBox tag_box(std::string_view text, int font_size, int x, int y) {
    // as draw_tag: the text's width plus a margin, centred, its outline included
    const int w = text_width(text, font_size) + font_size / 2 + 2;
    const int h = font_size + font_size / 4 + 2;
    return {x - w / 2, y - h / 2, x - w / 2 + w + 1, y - h / 2 + h + 1};
}

PixelBox text_box(std::string_view text, int font_size, int x, int y, TextAlign align) {
    const int w = text_width(text, font_size);
    const int left = align == TextAlign::Center ? x - w / 2 : align == TextAlign::Right ? x - w : x;
    return {left - 2, y - font_size - 2, left + w + 2, y + font_size / 4 + 2};
}

std::vector<PlacedLabel> place_labels(const std::vector<RegionAnchor>& anchors, int width,
                                      int height, int font_size, std::size_t min_pixels,
                                      const std::vector<PixelBox>& reserved) {
    std::vector<const RegionAnchor*> order;
    for (const auto& a : anchors)
        if (a.pixels >= min_pixels) order.push_back(&a);
    std::stable_sort(order.begin(), order.end(),
                     [](const auto* p, const auto* q) { return p->pixels > q->pixels; });
    std::vector<PixelBox> taken = reserved;
    std::vector<PlacedLabel> placed;
    for (const RegionAnchor* a : order) {
        const std::string text = std::to_string(a->id);
        const PixelBox probe = tag_box(text, font_size, 0, 0);
        const int w = probe.x1 - probe.x0, h = probe.y1 - probe.y0;
        PlacedLabel label{.id = a->id,
                          .box = tag_box(text, font_size, a->x, a->y),
                          .anchor_x = a->x,
                          .anchor_y = a->y};
        const auto spots = candidates(*a, w, h);
        for (std::size_t k = 0; k < spots.size(); ++k) {
            const PixelBox box = tag_box(text, font_size, spots[k].first, spots[k].second);
            if (!is_free(box, width, height, taken)) continue;
            label.box = box;
            // beside the region (the first ring's spots at its row or column) needs no leader
            label.has_leader = k >= 12;
            break;
        }
        taken.push_back(label.box);
        placed.push_back(label);
    }
    return placed;
}

void draw_region_numbers(Canvas& dst, int x0, int y0, int width, int height,
                         const std::vector<RegionAnchor>& anchors, int font_size,
                         std::size_t min_pixels, const std::vector<PixelBox>& reserved) {
    draw_labels(dst, x0, y0, place_labels(anchors, width, height, font_size, min_pixels, reserved),
                font_size);
}

void draw_labels(Canvas& dst, int x0, int y0, const std::vector<PlacedLabel>& labels,
                 int font_size) {
    for (const auto& l : labels) {
        if (!l.has_leader) continue;
        const int cx = (l.box.x0 + l.box.x1) / 2, cy = (l.box.y0 + l.box.y1) / 2;
        // A dark line under a light one: the leader reads on white and on the background.
        draw_line(dst, x0 + cx + 1, y0 + cy + 1, x0 + l.anchor_x + 1, y0 + l.anchor_y + 1,
                  kOutline);
        draw_line(dst, x0 + cx, y0 + cy, x0 + l.anchor_x, y0 + l.anchor_y, kText);
    }
    for (const auto& l : labels)
        draw_tag(dst, x0 + (l.box.x0 + l.box.x1 - 1) / 2, y0 + (l.box.y0 + l.box.y1 - 1) / 2,
                 std::to_string(l.id), font_size);
}

}  // namespace glint::detail
