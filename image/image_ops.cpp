#include "image/image_ops.h"

#include "image/detail/image_plugin.h"
#include "mesh/error.h"

namespace glint {

using detail::call_image_io;
using detail::ImageIoTable;

void preload_image_io() { detail::preload_image_io_plugin(); }

std::vector<float> color_map(std::span<const float> values, std::string_view map) {
    std::vector<float> rgb(3 * values.size());
    if (values.empty()) return rgb;
    const std::string name(map);
    call_image_io([&](const ImageIoTable& io, std::string& message) {
        return io.color_map(values.data(), values.size(), name.c_str(), nullptr, 0, rgb.data(),
                            message);
    });
    return rgb;
}

std::vector<float> color_map(std::span<const float> values, std::span<const float> knots) {
    GLINT_ASSERT(knots.size() >= 6 && knots.size() % 3 == 0, "colour map: knots are RGB triples");
    std::vector<float> rgb(3 * values.size());
    if (values.empty()) return rgb;
    call_image_io([&](const ImageIoTable& io, std::string& message) {
        return io.color_map(values.data(), values.size(), "", knots.data(),
                            static_cast<int>(knots.size() / 3), rgb.data(), message);
    });
    return rgb;
}

void draw_line(Canvas& canvas, int x0, int y0, int x1, int y1, const Rgb& colour) {
    if (canvas.empty()) return;
    call_image_io([&](const ImageIoTable& io, std::string& message) {
        return io.draw_line(canvas.view(), x0, y0, x1, y1, colour, message);
    });
}

void draw_box(Canvas& canvas, int x0, int y0, int x1, int y1, const Rgb& colour, bool fill) {
    if (canvas.empty()) return;
    call_image_io([&](const ImageIoTable& io, std::string& message) {
        return io.draw_box(canvas.view(), x0, y0, x1, y1, colour, fill, message);
    });
}

Canvas resize_nearest(const Canvas& source, int width, int height) {
    Canvas out(width, height, source.channels());
    if (out.empty() || source.empty()) return out;
    call_image_io([&](const ImageIoTable& io, std::string& message) {
        return io.resize_nearest(source.view(), out.view(), message);
    });
    return out;
}

std::string encode_png(const Canvas& canvas) {
    constexpr int kZlibLevel = 1;
    constexpr int kSubFilter = 16;  // libpng's PNG_FILTER_SUB
    std::string bytes;
    call_image_io([&](const ImageIoTable& io, std::string& message) {
        return io.encode_png(canvas.view(), kZlibLevel, kSubFilter, bytes, message);
    });
    return bytes;
}

void write_image_file(const std::filesystem::path& path, const FloatImage& image,
                      PixelFormat format, bool unassociated_alpha) {
    GLINT_ASSERT(image.pixels.size() == static_cast<std::size_t>(image.width) *
                                            static_cast<std::size_t>(image.height) *
                                            image.channel_names.size(),
                 "image file: pixels do not match the size and channels");
    call_image_io([&](const ImageIoTable& io, std::string& message) {
        return io.write_file(path, image, format, unassociated_alpha, message);
    });
}

FloatImage read_image_file(const std::filesystem::path& path) {
    FloatImage image;
    call_image_io([&](const ImageIoTable& io, std::string& message) {
        return io.read_file(path, image, message);
    });
    return image;
}

}  // namespace glint
