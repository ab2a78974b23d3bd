#include "report/images.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "report/detail/canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <utility>

namespace glint {

namespace fs = std::filesystem;

namespace {

void draw_text(Canvas& dst, int x, int y, const std::string& text, int size) {
    detail::draw_text(dst, x, y, text, size);
}

std::string format_value(double v, const std::string& unit) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g%s", v, unit.c_str());
    return buf;
}

// `image` coloured by `scale` (3 floats per pixel), NaN drawn grey.
std::vector<float> colour_values(const ScalarImage& image, const ColorScale& scale) {
    std::vector<float> scaled(image.values.size());
    const double span = scale.high > scale.low ? scale.high - scale.low : 1.0;
    for (std::size_t i = 0; i < scaled.size(); ++i) {
        const float v = image.values[i];
        scaled[i] =
            std::isnan(v) ? 0.0f : static_cast<float>(std::clamp((v - scale.low) / span, 0.0, 1.0));
    }
    // The diverging map from its build-time samples (the atlas files' colours load no image
    // library); the other maps through OpenImageIO, for pictures.
    std::vector<float> px;
    if (scale.map == "diverging") {
        px.resize(3 * scaled.size());
        const auto& table = detail::DivergingTable::get();
        for (std::size_t i = 0; i < scaled.size(); ++i) {
            const Rgb c = table.at(scaled[i]);
            std::copy(c.begin(), c.end(), px.begin() + static_cast<std::ptrdiff_t>(3 * i));
        }
    } else {
        px = color_map(scaled, scale.map);
    }
    for (std::size_t i = 0; i < image.values.size(); ++i)
        if (std::isnan(image.values[i]))
            px[3 * i] = px[3 * i + 1] = px[3 * i + 2] = scale.no_data_grey;
    return px;
}

Canvas colour_image(const ScalarImage& image, const ColorScale& scale) {
    const std::vector<float> px = colour_values(image, scale);
    std::vector<std::uint8_t> bytes(px.size());
    std::transform(px.begin(), px.end(), bytes.begin(), to_byte);
    return Canvas(image.width, image.height, 3, std::move(bytes));
}

// A vertical colour bar (high at the top) of the given size.
Canvas colour_bar(int width, int height, const ColorScale& scale) {
    ScalarImage ramp{
        width, height,
        std::vector<float>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            ramp.values[static_cast<std::size_t>(y * width + x)] = static_cast<float>(
                scale.high - (scale.high - scale.low) * y / std::max(1, height - 1));
    return colour_image(ramp, scale);
}

void write_png(const Canvas& canvas, const fs::path& path) {
    write_file_atomically(path, encode_png(canvas));
}

}  // namespace

std::vector<Rgb8> colorize(const std::vector<float>& values, const ColorScale& scale) {
    std::vector<Rgb8> out(values.size());
    if (values.empty()) return out;
    const ScalarImage row{static_cast<int>(values.size()), 1, values};
    const std::vector<float> px = colour_values(row, scale);
    for (std::size_t i = 0; i < values.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
            out[i][c] = static_cast<std::uint8_t>(
                std::lround(std::clamp(px[3 * i + c], 0.0f, 1.0f) * 255.0f));
    return out;
}

void write_heatmap_png(const ScalarImage& image, const ColorScale& scale, const std::string& title,
                       const fs::path& path) {
    GLINT_ASSERT(image.values.size() ==
                     static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height),
                 "heat map size does not match its values");
    constexpr int kTitle = 24;  // px reserved for the title line
    constexpr int kBar = 80;    // px reserved on the right: bar + numbers
    // note: coarse zooms give tiny frames; they are enlarged by an integer factor with
    // nearest-neighbour sampling (pixels stay visible as blocks) so the picture and its
    // title stay readable.
    constexpr int kMinWidth = 400;
    const int factor = std::max(1, (kMinWidth + image.width - 1) / std::max(1, image.width));
    Canvas picture = colour_image(image, scale);
    if (factor > 1) picture = resize_nearest(picture, image.width * factor, image.height * factor);
    const int pw = image.width * factor;
    const int ph = image.height * factor;
    Canvas sheet(pw + kBar, std::max(ph + kTitle, 120), 3, Rgb{0.05f, 0.05f, 0.05f});
    sheet.paste(picture, 0, kTitle);
    const int bar_h = std::max(40, ph - 20);
    sheet.paste(colour_bar(16, bar_h, scale), pw + 8, kTitle + 10);
    draw_text(sheet, 4, 17, title, 14);
    draw_text(sheet, pw + 28, kTitle + 20, format_value(scale.high, scale.unit), 12);
    draw_text(sheet, pw + 28, kTitle + 10 + bar_h, format_value(scale.low, scale.unit), 12);
    write_png(sheet, path);
}

void write_exr_channels(const fs::path& path, int width, int height,
                        const std::vector<std::string>& names,
                        const std::vector<const std::vector<float>*>& channels,
                        const std::vector<std::pair<std::string, std::string>>& metadata) {
    GLINT_ASSERT(names.size() == channels.size() && !names.empty(),
                 "EXR channels and names differ");
    FloatImage image{width, height, names, -1, -1, {}, {}};
    for (const auto& [key, value] : metadata) image.metadata.emplace_back("glint:" + key, value);
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    image.pixels.resize(n * names.size());
    for (std::size_t c = 0; c < channels.size(); ++c) {
        GLINT_ASSERT(channels[c]->size() == n, "EXR channel size mismatch");
        for (std::size_t i = 0; i < n; ++i)
            image.pixels[i * channels.size() + c] = (*channels[c])[i];
    }
    write_atomically_to_path(path, [&](const fs::path& temp) {
        try {
            write_image_file(temp, image, PixelFormat::Float);
        } catch (const IoError& e) {
            throw IoError("cannot write \"" + path.string() + "\": " + e.what());
        }
    });
}

}  // namespace glint
