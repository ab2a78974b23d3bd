// glint's own picture canvas: 8 bits per channel, row-major, top row first, channels
// interleaved (what the PNG pictures store). It is plain memory, so the program draws and
// composes pictures without mapping OpenImageIO; what OpenImageIO does well (colour maps,
// lines and boxes, resampling, PNG/EXR files) is done on this memory by the image plugin
// (image/image_ops.h), opened on first use.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace glint {

/// A colour of 0…1 channels (linear values written as 8-bit PNG).
using Rgb = std::array<float, 3>;

/// A channel value (0…1) as an 8-bit value, rounded as OpenImageIO converts.
[[nodiscard]] inline std::uint8_t to_byte(float v) {
    return static_cast<std::uint8_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
}

/// An 8-bit view of a canvas's memory (what the image plugin draws into).
struct PixelView {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::uint8_t* pixels = nullptr;
};
struct ConstPixelView {
    int width = 0;
    int height = 0;
    int channels = 0;
    const std::uint8_t* pixels = nullptr;
};

class Canvas {
  public:
    Canvas() = default;
    /// A width × height canvas of `channels` channels, filled with `colour` (alpha, if any, 1).
    Canvas(int width, int height, int channels = 3, Rgb colour = {0.0f, 0.0f, 0.0f});
    /// A canvas holding `pixels` (width × height × channels bytes, as view() lays them out).
    Canvas(int width, int height, int channels, std::vector<std::uint8_t> pixels);

    [[nodiscard]] int width() const { return width_; }
    [[nodiscard]] int height() const { return height_; }
    [[nodiscard]] int channels() const { return channels_; }
    [[nodiscard]] bool empty() const { return pixels_.empty(); }
    [[nodiscard]] bool contains(int x, int y) const {
        return x >= 0 && y >= 0 && x < width_ && y < height_;
    }

    /// Channel `c` of pixel (x, y) as 0…1, converted as OpenImageIO converts 8-bit values
    /// (k · (1/255)), so a pixel read here equals the same pixel read from the PNG file.
    /// \pre contains(x, y).
    [[nodiscard]] float value(int x, int y, int c) const {
        constexpr float kToFloat = 1.0f / 255.0f;
        return static_cast<float>(pixels_[offset(x, y) + static_cast<std::size_t>(c)]) * kToFloat;
    }
    /// The first three channels of pixel (x, y) as 0…1. \pre contains(x, y).
    [[nodiscard]] Rgb rgb(int x, int y) const {
        return {value(x, y, 0), value(x, y, 1), value(x, y, 2)};
    }
    /// Sets the first three channels of pixel (x, y); nothing outside the canvas.
    void set(int x, int y, const Rgb& colour) {
        if (!contains(x, y)) return;
        std::uint8_t* p = &pixels_[offset(x, y)];
        for (std::size_t c = 0; c < 3; ++c) p[c] = to_byte(colour[c]);
    }

    /// Fills the whole canvas with `colour`.
    void fill(const Rgb& colour);
    /// Copies `source` with its top-left corner at (x, y), clipped to this canvas; channels
    /// beyond the narrower of the two are left as they are.
    void paste(const Canvas& source, int x, int y);

    [[nodiscard]] PixelView view() { return {width_, height_, channels_, pixels_.data()}; }
    [[nodiscard]] ConstPixelView view() const {
        return {width_, height_, channels_, pixels_.data()};
    }
    [[nodiscard]] const std::vector<std::uint8_t>& pixels() const { return pixels_; }

  private:
    [[nodiscard]] std::size_t offset(int x, int y) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                static_cast<std::size_t>(x)) *
               static_cast<std::size_t>(channels_);
    }

    int width_ = 0;
    int height_ = 0;
    int channels_ = 0;
    std::vector<std::uint8_t> pixels_;
};

}  // namespace glint
