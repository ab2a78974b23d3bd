#include "render/image_io.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

namespace glint {

namespace fs = std::filesystem;

namespace {

std::string extension_of(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

void add_metadata(OIIO::ImageSpec& spec, const std::map<std::string, std::string>& metadata) {
    for (const auto& [key, value] : metadata) spec.attribute("glint:" + key, value);
}

void write_buffer(const fs::path& path, const OIIO::ImageSpec& spec, const float* pixels,
                  OIIO::TypeDesc format) {
    write_atomically_to_path(path, [&](const fs::path& temp) {
        auto out = OIIO::ImageOutput::create(temp.string());
        if (!out) {
            throw IoError("cannot write \"" + path.string() + "\": " + OIIO::geterror());
        }
        OIIO::ImageSpec file_spec = spec;
        file_spec.set_format(format);
        if (!out->open(temp.string(), file_spec)) {
            throw IoError("cannot write \"" + path.string() + "\": " + out->geterror());
        }
        if (!out->write_image(OIIO::TypeDesc::FLOAT, pixels)) {
            throw IoError("cannot write \"" + path.string() + "\": " + out->geterror());
        }
        if (!out->close()) {
            throw IoError("cannot write \"" + path.string() + "\": " + out->geterror());
        }
    });
}

OIIO::TypeDesc png_format(int bits) {
    if (bits != 8 && bits != 16) {
        throw InputError("png bits = " + std::to_string(bits) + ", expected 8 or 16");
    }
    return bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
}

}  // namespace

void write_rgba_image(const fs::path& path, const RgbaImage& image,
                      const std::map<std::string, std::string>& metadata, int png_bits) {
    const std::string ext = extension_of(path);
    if (ext != ".png" && ext != ".exr") {
        throw InputError("image \"" + path.string() + "\": extension must be .png or .exr");
    }
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B", "A"};
    spec.alpha_channel = 3;
    add_metadata(spec, metadata);
    if (ext == ".png") {
        // note: PNG stores straight (unassociated) alpha; our colour is not premultiplied.
        spec.attribute("oiio:UnassociatedAlpha", 1);
    }
    write_buffer(path, spec, image.pixels.data(),
                 ext == ".png" ? png_format(png_bits) : OIIO::TypeDesc::HALF);
}

void write_frame_image(const fs::path& path, const Frame& frame, const View& view,
                       const FrameImageOptions& options) {
    const std::string ext = extension_of(path);
    if (ext != ".png" && ext != ".exr") {
        throw InputError("image \"" + path.string() + "\": extension must be .png or .exr");
    }
    std::map<std::string, std::string> metadata = options.metadata;
    metadata["azimuth_deg"] = std::to_string(view.azimuth_deg);
    metadata["elevation_deg"] = std::to_string(view.elevation_deg);
    metadata["footprint"] = std::to_string(view.footprint);
    metadata["zoom_index"] = std::to_string(view.zoom_index);
    metadata["view_index"] = std::to_string(view.index);
    metadata["mode"] = to_string(options.shade.mode);
    metadata["normal_space"] = frame.normal_space == NormalSpace::World ? "world" : "view";
    metadata["projection"] =
        view.camera.projection == Projection::Orthographic ? "orthographic" : "perspective";
    const RgbaImage shaded = shade(frame, view, options.shade);
    if (ext == ".png") {
        write_rgba_image(path, shaded, metadata, options.png_bits);
        return;
    }
    // EXR: shaded colour + the raw numbers, all float (no 8- or 16-bit quantisation).
    constexpr int kChannels = 9;
    const std::size_t n = frame.pixel_count();
    std::vector<float> pixels(kChannels * n);
    for (std::size_t p = 0; p < n; ++p) {
        float* px = &pixels[kChannels * p];
        for (int c = 0; c < 4; ++c) px[c] = shaded.pixels[4 * p + static_cast<std::size_t>(c)];
        for (int c = 0; c < 3; ++c) px[4 + c] = frame.normal[3 * p + static_cast<std::size_t>(c)];
        px[7] = frame.depth[p];
        px[8] = frame.primitive_id[p] == kNoPrimitive ? -1.0f
                                                      : static_cast<float>(frame.primitive_id[p]);
    }
    OIIO::ImageSpec spec(frame.width, frame.height, kChannels, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B", "A", "N.x", "N.y", "N.z", "Z", "id"};
    spec.alpha_channel = 3;
    spec.z_channel = 7;
    add_metadata(spec, metadata);
    write_buffer(path, spec, pixels.data(), OIIO::TypeDesc::FLOAT);
}

}  // namespace glint
