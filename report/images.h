// Heat maps with a colour bar (glint compare), EXR channels, vertex colours. The pictures of a
// sweep (views, mosaics, atlas.png) are report/pictures.h's.
// All colour mapping goes through OpenImageIO's ImageBufAlgo::color_map (image/image_ops.h, the
// image plugin); files are written atomically (temporary name, then rename).
#pragma once

#include "mesh/mesh.h"

#include <filesystem>
#include <string>
#include <vector>

namespace glint {

/// A single-channel float image, row-major, top row first; NaN marks "no data".
struct ScalarImage {
    int width = 0;
    int height = 0;
    std::vector<float> values;
};

/// How values map to colour: [low, high] onto an OIIO colour map ("inferno", "viridis",
/// "turbo"; "diverging": the pictures' map of signed shape change, blue → white → red);
/// NaN pixels are drawn in `no_data_grey`.
struct ColorScale {
    double low = 0.0;
    double high = 1.0;
    std::string map = "inferno";
    std::string unit = " deg";
    float no_data_grey = 0.18f;
};

/// Colours of per-vertex values (NaN → grey), through ImageBufAlgo::color_map.
[[nodiscard]] std::vector<Rgb8> colorize(const std::vector<float>& values, const ColorScale& scale);

/// Writes a heat map PNG: the image coloured by `scale`, a title line on top and a colour bar
/// with its range on the right. \throw IoError naming the path and OIIO's message.
void write_heatmap_png(const ScalarImage& image, const ColorScale& scale, const std::string& title,
                       const std::filesystem::path& path);

/// Writes named float channels (same size) into one EXR with string metadata.
/// \throw IoError.
void write_exr_channels(const std::filesystem::path& path, int width, int height,
                        const std::vector<std::string>& names,
                        const std::vector<const std::vector<float>*>& channels,
                        const std::vector<std::pair<std::string, std::string>>& metadata);

}  // namespace glint
