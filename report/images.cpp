#include "report/images.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "report/detail/canvas.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

namespace glint {

namespace fs = std::filesystem;
using OIIO::ImageBuf;
using OIIO::ImageSpec;
using OIIO::ROI;
using OIIO::TypeDesc;
namespace IBA = OIIO::ImageBufAlgo;

namespace {

void draw_text(ImageBuf& dst, int x, int y, const std::string& text, int size) {
    detail::draw_text(dst, x, y, text, size);
}

std::string format_value(double v, const std::string& unit) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g%s", v, unit.c_str());
    return buf;
}

// RGB float image of `image` coloured by `scale`, NaN drawn grey.
ImageBuf colour_image(const ScalarImage& image, const ColorScale& scale) {
    ImageSpec spec(image.width, image.height, 1, TypeDesc::FLOAT);
    ImageBuf norm(spec);
    std::vector<float> scaled(image.values.size());
    const double span = scale.high > scale.low ? scale.high - scale.low : 1.0;
    for (std::size_t i = 0; i < scaled.size(); ++i) {
        const float v = image.values[i];
        scaled[i] =
            std::isnan(v) ? 0.0f : static_cast<float>(std::clamp((v - scale.low) / span, 0.0, 1.0));
    }
    norm.set_pixels(ROI(0, image.width, 0, image.height, 0, 1, 0, 1), TypeDesc::FLOAT,
                    scaled.data());
    const auto knots = detail::diverging_knots();
    ImageBuf rgb =
        scale.map == "diverging"
            ? IBA::color_map(norm, 0, 9, 3, OIIO::cspan<float>(knots.data(), knots.size()))
            : IBA::color_map(norm, 0, scale.map);
    if (rgb.has_error()) throw IoError("colour map '" + scale.map + "': " + rgb.geterror());
    // Grey where there is no data (patched in a plain buffer: per-pixel setpixel is slow).
    const ROI all(0, image.width, 0, image.height, 0, 1, 0, 3);
    std::vector<float> px(image.values.size() * 3);
    rgb.get_pixels(all, TypeDesc::FLOAT, px.data());
    for (std::size_t i = 0; i < image.values.size(); ++i)
        if (std::isnan(image.values[i]))
            px[3 * i] = px[3 * i + 1] = px[3 * i + 2] = scale.no_data_grey;
    rgb.set_pixels(all, TypeDesc::FLOAT, px.data());
    return rgb;
}

// A vertical colour bar (high at the top) of the given size.
ImageBuf colour_bar(int width, int height, const ColorScale& scale) {
    ScalarImage ramp{
        width, height,
        std::vector<float>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            ramp.values[static_cast<std::size_t>(y * width + x)] = static_cast<float>(
                scale.high - (scale.high - scale.low) * y / std::max(1, height - 1));
    return colour_image(ramp, scale);
}

void write_png(const ImageBuf& buf, const fs::path& path) {
    write_atomically_to_path(path, [&](const fs::path& temp) {
        if (!buf.write(temp.string(), TypeDesc::UINT8))
            throw IoError("cannot write \"" + path.string() + "\": " + buf.geterror());
    });
}

}  // namespace

std::vector<Rgb8> colorize(const std::vector<float>& values, const ColorScale& scale) {
    std::vector<Rgb8> out(values.size());
    if (values.empty()) return out;
    const ScalarImage row{static_cast<int>(values.size()), 1, values};
    const ImageBuf rgb = colour_image(row, scale);
    std::vector<float> px(values.size() * 3);
    rgb.get_pixels(ROI(0, row.width, 0, 1, 0, 1, 0, 3), TypeDesc::FLOAT, px.data());
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
    ImageBuf picture = colour_image(image, scale);
    if (factor > 1)
        picture = IBA::resample(picture, false,
                                ROI(0, image.width * factor, 0, image.height * factor, 0, 1, 0, 3));
    const int pw = image.width * factor;
    const int ph = image.height * factor;
    ImageBuf sheet(ImageSpec(pw + kBar, std::max(ph + kTitle, 120), 3, TypeDesc::FLOAT));
    const float black[3] = {0.05f, 0.05f, 0.05f};
    IBA::fill(sheet, black);
    IBA::paste(sheet, 0, kTitle, 0, 0, picture);
    const int bar_h = std::max(40, ph - 20);
    IBA::paste(sheet, pw + 8, kTitle + 10, 0, 0, colour_bar(16, bar_h, scale));
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
    const int nc = static_cast<int>(names.size());
    ImageSpec spec(width, height, nc, TypeDesc::FLOAT);
    spec.channelnames = names;
    for (const auto& [key, value] : metadata) spec.attribute("glint:" + key, value);
    ImageBuf buf(spec);
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<float> interleaved(n * static_cast<std::size_t>(nc));
    for (std::size_t c = 0; c < channels.size(); ++c) {
        GLINT_ASSERT(channels[c]->size() == n, "EXR channel size mismatch");
        for (std::size_t i = 0; i < n; ++i)
            interleaved[i * channels.size() + c] = (*channels[c])[i];
    }
    buf.set_pixels(ROI(0, width, 0, height, 0, 1, 0, nc), TypeDesc::FLOAT, interleaved.data());
    write_atomically_to_path(path, [&](const fs::path& temp) {
        if (!buf.write(temp.string(), TypeDesc::FLOAT))
            throw IoError("cannot write \"" + path.string() + "\": " + buf.geterror());
    });
}

}  // namespace glint
