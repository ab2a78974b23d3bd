// The image plugin: the table of image/plugin/image_io_abi.h on OpenImageIO. Drawing wraps
// the program's canvas memory in an ImageBuf (no copy) and runs ImageBufAlgo on it; files
// go through ImageInput/ImageOutput. Each entry turns an exception into (kind, message).
#include "image/plugin/image_io_abi.h"
#include "mesh/error.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

namespace glint::detail {
namespace {

namespace IBA = OIIO::ImageBufAlgo;

OIIO::ImageSpec spec_of(int width, int height, int channels, OIIO::TypeDesc type) {
    return OIIO::ImageSpec(width, height, channels, type);
}

// The canvas's memory as an ImageBuf that reads and writes it in place.
OIIO::ImageBuf wrap(const PixelView& v) {
    return OIIO::ImageBuf(spec_of(v.width, v.height, v.channels, OIIO::TypeDesc::UINT8), v.pixels);
}
OIIO::ImageBuf wrap(const ConstPixelView& v) {
    // note: ImageBuf takes a writable pointer; the buffer is only read here.
    return OIIO::ImageBuf(spec_of(v.width, v.height, v.channels, OIIO::TypeDesc::UINT8),
                          const_cast<std::uint8_t*>(v.pixels));
}

void check(const OIIO::ImageBuf& buf, bool ok, const char* what) {
    if (!ok || buf.has_error()) throw IoError(std::string(what) + ": " + buf.geterror());
}

void color_map_values(const float* values, std::size_t count, const char* map_name,
                      const float* knots, int knot_count, float* rgb) {
    const int n = static_cast<int>(count);
    OIIO::ImageBuf scalar(spec_of(n, 1, 1, OIIO::TypeDesc::FLOAT));
    scalar.set_pixels(OIIO::ROI(0, n, 0, 1, 0, 1, 0, 1), OIIO::TypeDesc::FLOAT, values);
    const OIIO::ImageBuf mapped =
        knot_count > 0
            ? IBA::color_map(scalar, 0, knot_count, 3,
                             OIIO::cspan<float>(knots, static_cast<std::size_t>(3 * knot_count)))
            : IBA::color_map(scalar, 0, map_name);
    if (mapped.has_error())
        throw InputError(std::string("colour map '") + (knot_count > 0 ? "knots" : map_name) +
                         "': " + mapped.geterror());
    check(mapped, mapped.get_pixels(OIIO::ROI(0, n, 0, 1, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, rgb),
          "colour map");
}

void write_image_file(const std::filesystem::path& path, const FloatImage& image,
                      PixelFormat format, bool unassociated_alpha) {
    const auto nc = static_cast<int>(image.channel_names.size());
    OIIO::ImageSpec spec(image.width, image.height, nc, OIIO::TypeDesc::FLOAT);
    spec.channelnames = image.channel_names;
    spec.alpha_channel = image.alpha_channel;
    spec.z_channel = image.z_channel;
    for (const auto& [key, value] : image.metadata) spec.attribute(key, value);
    if (unassociated_alpha) spec.attribute("oiio:UnassociatedAlpha", 1);
    constexpr OIIO::TypeDesc::BASETYPE kTypes[] = {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16,
                                                   OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT};
    spec.set_format(kTypes[static_cast<int>(format)]);
    const std::string name = path.string();
    auto out = OIIO::ImageOutput::create(name);
    if (!out) throw IoError("cannot write \"" + name + "\": " + OIIO::geterror());
    if (!out->open(name, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) ||
        !out->close())
        throw IoError("cannot write \"" + name + "\": " + out->geterror());
}

void read_image_file(const std::filesystem::path& path, FloatImage& out) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw InputError("cannot read as an image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    out = FloatImage{};
    out.width = spec.width;
    out.height = spec.height;
    for (int c = 0; c < spec.nchannels; ++c) out.channel_names.emplace_back(spec.channel_name(c));
    out.alpha_channel = spec.alpha_channel;
    out.z_channel = spec.z_channel;
    for (const OIIO::ParamValue& p : spec.extra_attribs)
        if (p.type() == OIIO::TypeDesc::STRING)
            out.metadata.emplace_back(p.name().string(), p.get_string());
    out.pixels.resize(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                      static_cast<std::size_t>(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.pixels.data()))
        throw IoError(in->geterror());
}

PluginErrorKind color_map(const float* values, std::size_t count, const char* map_name,
                          const float* knots, int knot_count, float* rgb,
                          std::string& message) noexcept {
    return plugin_guarded(
        message, [&] { color_map_values(values, count, map_name, knots, knot_count, rgb); });
}

PluginErrorKind draw_line(const PixelView& image, int x0, int y0, int x1, int y1, const Rgb& colour,
                          std::string& message) noexcept {
    return plugin_guarded(message, [&] {
        OIIO::ImageBuf buf = wrap(image);
        check(buf, IBA::render_line(buf, x0, y0, x1, y1, colour), "line");
    });
}

PluginErrorKind draw_box(const PixelView& image, int x0, int y0, int x1, int y1, const Rgb& colour,
                         bool fill, std::string& message) noexcept {
    return plugin_guarded(message, [&] {
        OIIO::ImageBuf buf = wrap(image);
        check(buf, IBA::render_box(buf, x0, y0, x1, y1, colour, fill), "box");
    });
}

PluginErrorKind resize_nearest(const ConstPixelView& source, const PixelView& target,
                               std::string& message) noexcept {
    return plugin_guarded(message, [&] {
        const OIIO::ImageBuf src = wrap(source);
        OIIO::ImageBuf dst = wrap(target);
        check(dst, IBA::resample(dst, src, false), "resample");
    });
}

PluginErrorKind encode_png(const ConstPixelView& image, int level, int filter, std::string& bytes,
                           std::string& message) noexcept {
    return plugin_guarded(message, [&] {
        std::vector<unsigned char> out;
        OIIO::Filesystem::IOVecOutput proxy(out);
        OIIO::ImageBuf buf = wrap(image);
        buf.set_write_ioproxy(&proxy);
        buf.specmod().attribute("png:compressionLevel", level);
        buf.specmod().attribute("png:filter", filter);
        if (!buf.write("picture.png", OIIO::TypeDesc::UINT8, "png"))
            throw IoError("cannot encode a PNG picture: " + buf.geterror());
        bytes.assign(out.begin(), out.end());
    });
}

PluginErrorKind write_file(const std::filesystem::path& path, const FloatImage& image,
                           PixelFormat format, bool unassociated_alpha,
                           std::string& message) noexcept {
    return plugin_guarded(message,
                          [&] { write_image_file(path, image, format, unassociated_alpha); });
}

PluginErrorKind read_file(const std::filesystem::path& path, FloatImage& out,
                          std::string& message) noexcept {
    return plugin_guarded(message, [&] { read_image_file(path, out); });
}

constexpr ImageIoTable kTable{sizeof(ImageIoTable), color_map,  draw_line,  draw_box,
                              resize_nearest,       encode_png, write_file, read_file};

}  // namespace
}  // namespace glint::detail

extern "C" __attribute__((visibility("default"))) const glint::detail::ImageIoTable*
glint_image_io_table_v1() {
    return &glint::detail::kTable;
}
