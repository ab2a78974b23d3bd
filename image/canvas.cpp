#include "image/canvas.h"

#include "mesh/error.h"

#include <cstring>
#include <utility>

namespace glint {

Canvas::Canvas(int width, int height, int channels, Rgb colour)
    : width_(width), height_(height), channels_(channels) {
    GLINT_ASSERT(width >= 0 && height >= 0 && channels >= 3 && channels <= 4,
                 "canvas: 3 or 4 channels and no negative size");
    pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                       static_cast<std::size_t>(channels),
                   255);
    fill(colour);
}

Canvas::Canvas(int width, int height, int channels, std::vector<std::uint8_t> pixels)
    : width_(width), height_(height), channels_(channels), pixels_(std::move(pixels)) {
    GLINT_ASSERT(width >= 0 && height >= 0 && channels >= 3 && channels <= 4 &&
                     pixels_.size() == static_cast<std::size_t>(width) *
                                           static_cast<std::size_t>(height) *
                                           static_cast<std::size_t>(channels),
                 "canvas: its pixels do not match its size");
}

void Canvas::fill(const Rgb& colour) {
    const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    const std::array<std::uint8_t, 3> rgb{to_byte(colour[0]), to_byte(colour[1]),
                                          to_byte(colour[2])};
    for (std::size_t i = 0; i < n; ++i)
        std::memcpy(&pixels_[i * static_cast<std::size_t>(channels_)], rgb.data(), 3);
}

void Canvas::paste(const Canvas& source, int x, int y) {
    const int x0 = std::max(0, x), x1 = std::min(width_, x + source.width_);
    const int y0 = std::max(0, y), y1 = std::min(height_, y + source.height_);
    if (x0 >= x1 || y0 >= y1) return;
    const int nc = std::min(channels_, source.channels_);
    for (int row = y0; row < y1; ++row) {
        if (nc == channels_ && nc == source.channels_) {
            std::memcpy(&pixels_[offset(x0, row)], &source.pixels_[source.offset(x0 - x, row - y)],
                        static_cast<std::size_t>(x1 - x0) * static_cast<std::size_t>(nc));
            continue;
        }
        for (int col = x0; col < x1; ++col)
            std::memcpy(&pixels_[offset(col, row)],
                        &source.pixels_[source.offset(col - x, row - y)],
                        static_cast<std::size_t>(nc));
    }
}

}  // namespace glint
