// Pictures people look at: heat maps with a colour bar, mosaics of views, vertex colours.
// All colour mapping goes through OpenImageIO's ImageBufAlgo::color_map; files are written
// atomically (temporary name, then rename).
#pragma once

#include "mesh/mesh.h"

#include <filesystem>
#include <memory>
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
/// "turbo", "blue-red" for signed data); NaN pixels are drawn in `no_data_grey`.
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

/// A sheet of thumbnails in a grid (columns × rows), each labelled, built tile by tile so a
/// sweep never holds its full-size frames. Thumbnails are resized with OIIO.
class Mosaic {
public:
    Mosaic(int columns, int rows, int tile_size, std::string title);
    ~Mosaic();
    Mosaic(Mosaic&&) noexcept;
    Mosaic& operator=(Mosaic&&) noexcept;
    /// Colours `image` with `scale`, shrinks it to the tile size and places it at (column, row).
    void place(int column, int row, const ScalarImage& image, const ColorScale& scale,
               const std::string& label);
    /// Adds row/column headings and a colour bar, then writes a PNG atomically.
    void write(const std::filesystem::path& path, const ColorScale& scale,
               const std::vector<std::string>& column_labels,
               const std::vector<std::string>& row_labels) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace glint
