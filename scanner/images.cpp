#include "scanner/images.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <filesystem>

namespace glint {

namespace fs = std::filesystem;
using OIIO::ImageBuf;
using OIIO::ImageSpec;
using OIIO::ROI;
using OIIO::TypeDesc;
namespace IBA = OIIO::ImageBufAlgo;

namespace {

// note: DejaVu comes with fonts-dejavu-core (tools/setup installs it); OIIO searches
// /usr/share/fonts only one level deep, so the full path is given when it exists.
std::string font_path() {
    const char* candidates[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"};
    for (const char* c : candidates)
        if (fs::exists(c)) return c;
    return "";
}

// Text is decoration: when no font can be found the picture is still written, unlabelled.
void draw_text(ImageBuf& dst, int x, int y, const std::string& text, int size,
               float grey = 1.0f, IBA::TextAlignX align = IBA::TextAlignX::Left) {
    static const std::string font = font_path();
    if (font.empty()) return;
    const float colour[3] = {grey, grey, grey};
    IBA::render_text(dst, x, y, text, size, font, colour, align, IBA::TextAlignY::Baseline, 0);
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
        scaled[i] = std::isnan(v) ? 0.0f
                                  : static_cast<float>(std::clamp((v - scale.low) / span, 0.0, 1.0));
    }
    norm.set_pixels(ROI(0, image.width, 0, image.height, 0, 1, 0, 1), TypeDesc::FLOAT, scaled.data());
    ImageBuf rgb = IBA::color_map(norm, 0, scale.map);
    if (rgb.has_error()) throw IoError("colour map '" + scale.map + "': " + rgb.geterror());
    // Grey where there is no data (patched in a plain buffer: per-pixel setpixel is slow).
    const ROI all(0, image.width, 0, image.height, 0, 1, 0, 3);
    std::vector<float> px(image.values.size() * 3);
    rgb.get_pixels(all, TypeDesc::FLOAT, px.data());
    for (std::size_t i = 0; i < image.values.size(); ++i)
        if (std::isnan(image.values[i])) px[3 * i] = px[3 * i + 1] = px[3 * i + 2] = scale.no_data_grey;
    rgb.set_pixels(all, TypeDesc::FLOAT, px.data());
    return rgb;
}

// A vertical colour bar (high at the top) of the given size.
ImageBuf colour_bar(int width, int height, const ColorScale& scale) {
    ScalarImage ramp{width, height, std::vector<float>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
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
            out[i][c] = static_cast<std::uint8_t>(std::lround(std::clamp(px[3 * i + c], 0.0f, 1.0f) * 255.0f));
    return out;
}

void write_heatmap_png(const ScalarImage& image, const ColorScale& scale, const std::string& title,
                       const fs::path& path) {
    GLINT_ASSERT(image.values.size() == static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height),
                 "heat map size does not match its values");
    constexpr int kTitle = 24;   // px reserved for the title line
    constexpr int kBar = 80;     // px reserved on the right: bar + numbers
    // note: coarse zooms give tiny frames; they are enlarged by an integer factor with
    // nearest-neighbour sampling (pixels stay visible as blocks) so the picture and its
    // title stay readable.
    constexpr int kMinWidth = 400;
    const int factor = std::max(1, (kMinWidth + image.width - 1) / std::max(1, image.width));
    ImageBuf picture = colour_image(image, scale);
    if (factor > 1)
        picture = IBA::resample(picture, false, ROI(0, image.width * factor, 0, image.height * factor, 0, 1, 0, 3));
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
    GLINT_ASSERT(names.size() == channels.size() && !names.empty(), "EXR channels and names differ");
    const int nc = static_cast<int>(names.size());
    ImageSpec spec(width, height, nc, TypeDesc::FLOAT);
    spec.channelnames = names;
    for (const auto& [key, value] : metadata) spec.attribute("glint:" + key, value);
    ImageBuf buf(spec);
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<float> interleaved(n * static_cast<std::size_t>(nc));
    for (std::size_t c = 0; c < channels.size(); ++c) {
        GLINT_ASSERT(channels[c]->size() == n, "EXR channel size mismatch");
        for (std::size_t i = 0; i < n; ++i) interleaved[i * channels.size() + c] = (*channels[c])[i];
    }
    buf.set_pixels(ROI(0, width, 0, height, 0, 1, 0, nc), TypeDesc::FLOAT, interleaved.data());
    write_atomically_to_path(path, [&](const fs::path& temp) {
        if (!buf.write(temp.string(), TypeDesc::FLOAT))
            throw IoError("cannot write \"" + path.string() + "\": " + buf.geterror());
    });
}

struct Mosaic::Impl {
    int columns;
    int rows;
    int tile;
    std::string title;
    ImageBuf sheet;
    static constexpr int kHeader = 28;  // title line
    static constexpr int kRowLabel = 56;
    static constexpr int kColLabel = 18;
    static constexpr int kGap = 2;
    static constexpr int kBar = 90;
    [[nodiscard]] int x0(int c) const { return kRowLabel + c * (tile + kGap); }
    [[nodiscard]] int y0(int r) const { return kHeader + kColLabel + r * (tile + kGap); }
};

Mosaic::Mosaic(int columns, int rows, int tile_size, std::string title)
    : impl_(std::make_unique<Impl>()) {
    impl_->columns = columns;
    impl_->rows = rows;
    impl_->tile = tile_size;
    impl_->title = std::move(title);
    const int w = impl_->x0(columns) + Impl::kBar;
    const int h = std::max(impl_->y0(rows) + 4, Impl::kHeader + 160);
    impl_->sheet.reset(ImageSpec(w, h, 3, TypeDesc::FLOAT));
    const float black[3] = {0.05f, 0.05f, 0.05f};
    IBA::fill(impl_->sheet, black);
}

Mosaic::~Mosaic() = default;
Mosaic::Mosaic(Mosaic&&) noexcept = default;
Mosaic& Mosaic::operator=(Mosaic&&) noexcept = default;

void Mosaic::place(int column, int row, const ScalarImage& image, const ColorScale& scale,
                   const std::string& label) {
    GLINT_ASSERT(column >= 0 && column < impl_->columns && row >= 0 && row < impl_->rows,
                 "mosaic cell out of range");
    const int t = impl_->tile;
    // Keep the aspect ratio inside the square tile.
    const double s = static_cast<double>(t) / std::max(image.width, image.height);
    const int tw = std::max(1, static_cast<int>(std::lround(image.width * s)));
    const int th = std::max(1, static_cast<int>(std::lround(image.height * s)));
    // The tile keeps each block's largest deviation (NaN = no data only where the whole block
    // has none), then is coloured: a damage a few pixels wide stays visible in the mosaic,
    // where a filtered resize would dilute it. (Colouring the whole frame and resizing its
    // RGB with OIIO's filter also took ~40% of a sweep's time, perf on a 72-view sweep.)
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    ScalarImage tile{tw, th, std::vector<float>(static_cast<std::size_t>(tw) * static_cast<std::size_t>(th), kNaN)};
    for (int ty = 0; ty < th; ++ty) {
        const int y0 = ty * image.height / th;
        const int y1 = std::max(y0 + 1, (ty + 1) * image.height / th);
        for (int tx = 0; tx < tw; ++tx) {
            const int x0 = tx * image.width / tw;
            const int x1 = std::max(x0 + 1, (tx + 1) * image.width / tw);
            float& out = tile.values[static_cast<std::size_t>(ty) * static_cast<std::size_t>(tw) + static_cast<std::size_t>(tx)];
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const float v = image.values[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                                 static_cast<std::size_t>(x)];
                    if (!std::isnan(v) && (std::isnan(out) || v > out)) out = v;
                }
        }
    }
    const ImageBuf small = colour_image(tile, scale);
    IBA::paste(impl_->sheet, impl_->x0(column) + (t - tw) / 2, impl_->y0(row) + (t - th) / 2, 0, 0, small);
    if (!label.empty()) draw_text(impl_->sheet, impl_->x0(column) + 3, impl_->y0(row) + 12, label, 10, 0.9f);
}

void Mosaic::write(const fs::path& path, const ColorScale& scale,
                   const std::vector<std::string>& column_labels,
                   const std::vector<std::string>& row_labels) const {
    ImageBuf sheet = impl_->sheet;  // labels go on a copy so write() can be called again
    draw_text(sheet, 6, 20, impl_->title, 16);
    for (std::size_t c = 0; c < column_labels.size() && static_cast<int>(c) < impl_->columns; ++c)
        draw_text(sheet, impl_->x0(static_cast<int>(c)) + impl_->tile / 2, Impl::kHeader + 13,
                  column_labels[c], 11, 1.0f, IBA::TextAlignX::Center);
    for (std::size_t r = 0; r < row_labels.size() && static_cast<int>(r) < impl_->rows; ++r)
        draw_text(sheet, 4, impl_->y0(static_cast<int>(r)) + impl_->tile / 2 + 4, row_labels[r], 11);
    const int bar_x = impl_->x0(impl_->columns) + 8;
    const int bar_h = std::max(60, std::min(impl_->y0(impl_->rows) - Impl::kHeader - 40, 400));
    IBA::paste(sheet, bar_x, Impl::kHeader + 20, 0, 0, colour_bar(16, bar_h, scale));
    draw_text(sheet, bar_x + 20, Impl::kHeader + 30, format_value(scale.high, scale.unit), 11);
    draw_text(sheet, bar_x + 20, Impl::kHeader + 20 + bar_h, format_value(scale.low, scale.unit), 11);
    write_png(sheet, path);
}

}  // namespace glint
