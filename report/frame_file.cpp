#include "report/frame_file.h"

#include "mesh/error.h"

#include <OpenImageIO/imageio.h>

#include <cmath>

namespace glint {

Frame read_frame_exr(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError("frame \"" + path.string() + "\": no such file");
    auto in = OIIO::ImageInput::open(path.string());
    if (!in)
        throw InputError("frame \"" + path.string() +
                         "\": cannot read as an image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    auto channel = [&](const char* name) {
        for (int c = 0; c < spec.nchannels; ++c)
            if (spec.channel_name(c) == name) return c;
        throw InputError("frame \"" + path.string() + "\": no channel '" + name +
                         "', expected an EXR written by glint render (N.x N.y N.z Z id A)");
    };
    const int nx = channel("N.x"), ny = channel("N.y"), nz = channel("N.z"), z = channel("Z"),
              id = channel("id"), a = channel("A");
    std::vector<float> px(static_cast<std::size_t>(spec.width) *
                          static_cast<std::size_t>(spec.height) *
                          static_cast<std::size_t>(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()))
        throw IoError("frame \"" + path.string() + "\": " + in->geterror());
    Frame f = make_empty_frame(spec.width, spec.height);
    const auto nc = static_cast<std::size_t>(spec.nchannels);
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
