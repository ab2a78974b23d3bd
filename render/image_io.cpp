#include "render/image_io.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"

#include "image/image_ops.h"

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

void add_metadata(FloatImage& image, const std::map<std::string, std::string>& metadata) {
    for (const auto& [key, value] : metadata) image.metadata.emplace_back("glint:" + key, value);
}

void write_buffer(const fs::path& path, const FloatImage& image, PixelFormat format,
                  bool unassociated_alpha) {
    write_atomically_to_path(path, [&](const fs::path& temp) {
        try {
            write_image_file(temp, image, format, unassociated_alpha);
        } catch (const IoError& e) {
            throw IoError("cannot write \"" + path.string() + "\": " + e.what());
        }
    });
}

PixelFormat png_format(int bits) {
    if (bits != 8 && bits != 16) {
        throw InputError("png bits = " + std::to_string(bits) + ", expected 8 or 16");
    }
    return bits == 8 ? PixelFormat::UInt8 : PixelFormat::UInt16;
}

}  // namespace

void write_rgba_image(const fs::path& path, const RgbaImage& image,
                      const std::map<std::string, std::string>& metadata, int png_bits) {
    const std::string ext = extension_of(path);
    if (ext != ".png" && ext != ".exr") {
        throw InputError("image \"" + path.string() + "\": extension must be .png or .exr");
    }
    FloatImage file{image.width, image.height, {"R", "G", "B", "A"}, 3, -1, image.pixels, {}};
    add_metadata(file, metadata);
    // note: PNG stores straight (unassociated) alpha; our colour is not premultiplied.
    const bool png = ext == ".png";
    write_buffer(path, file, png ? png_format(png_bits) : PixelFormat::Half, png);
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
    FloatImage file{frame.width,
                    frame.height,
                    {"R", "G", "B", "A", "N.x", "N.y", "N.z", "Z", "id"},
                    3,
                    7,
                    std::vector<float>(kChannels * n),
                    {}};
    std::vector<float>& pixels = file.pixels;
    for (std::size_t p = 0; p < n; ++p) {
        float* px = &pixels[kChannels * p];
        for (int c = 0; c < 4; ++c) px[c] = shaded.pixels[4 * p + static_cast<std::size_t>(c)];
        for (int c = 0; c < 3; ++c) px[4 + c] = frame.normal[3 * p + static_cast<std::size_t>(c)];
        px[7] = frame.depth[p];
        px[8] = frame.primitive_id[p] == kNoPrimitive ? -1.0f
                                                      : static_cast<float>(frame.primitive_id[p]);
    }
    add_metadata(file, metadata);
    write_buffer(path, file, PixelFormat::Float, false);
}

}  // namespace glint
