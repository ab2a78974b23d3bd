#include "report/frame_file.h"

#include "image/image_ops.h"
#include "mesh/error.h"
#include "mesh/input_path.h"

#include <cmath>

namespace glint {

Frame read_frame_exr(const std::filesystem::path& path) {
    const std::string where = "frame \"" + path.string() + "\"";
    if (!reachable_input(path, where)) throw InputError(where + ": no such file");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(where + ": is not a regular file, expected an EXR frame");
    FloatImage image;
    try {
        image = read_image_file(path);
    } catch (const InputError& e) {
        throw InputError("frame \"" + path.string() + "\": " + e.what());
    } catch (const IoError& e) {
        throw IoError("frame \"" + path.string() + "\": " + e.what());
    }
    const auto nchannels = static_cast<int>(image.channel_names.size());
    auto channel = [&](const char* name) {
        for (int c = 0; c < nchannels; ++c)
            if (image.channel_names[static_cast<std::size_t>(c)] == name) return c;
        throw InputError("frame \"" + path.string() + "\": no channel '" + name +
                         "', expected an EXR written by glint render (N.x N.y N.z Z id A)");
    };
    const int nx = channel("N.x"), ny = channel("N.y"), nz = channel("N.z"), z = channel("Z"),
              id = channel("id"), a = channel("A");
    const std::vector<float>& px = image.pixels;
    Frame f = make_empty_frame(image.width, image.height);
    const auto nc = static_cast<std::size_t>(nchannels);
    for (std::size_t i = 0; i < f.pixel_count(); ++i) {
        const float* p = &px[i * nc];
        f.coverage[i] = p[a];
        if (!(p[a] > 0.0f)) continue;
        f.normal[3 * i] = p[nx];
        f.normal[3 * i + 1] = p[ny];
        f.normal[3 * i + 2] = p[nz];
        f.depth[i] = p[z];
        f.primitive_id[i] =
            p[id] >= 0.0f ? static_cast<std::uint32_t>(std::lround(p[id])) : kNoPrimitive;
    }
    return f;
}

}  // namespace glint
