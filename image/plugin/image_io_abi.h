// The table of functions libglint_image_io.so (image/plugin/) hands the main program: the only
// bridge to OpenImageIO, opened with dlopen by the first run that draws a picture or reads or
// writes an image file (image/detail/image_plugin.cpp), so other runs (glint --version,
// --help, info, a sweep without pictures) never map OpenImageIO and the ~240 libraries Debian
// builds it with.
//
// As for the volume plugin (volume/plugin/volume_io_abi.h): glint's own C++ types, one build,
// the version in the entry's name, no exception across the boundary (mesh/plugin_abi.h).
#pragma once

#include "image/canvas.h"
#include "mesh/plugin_abi.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace glint {

/// An image file's content as float channels (interleaved, row-major, top row first).
struct FloatImage {
    int width = 0;
    int height = 0;
    std::vector<std::string> channel_names;  ///< one per channel
    int alpha_channel = -1;                  ///< -1: none
    int z_channel = -1;                      ///< -1: none
    std::vector<float> pixels;               ///< width × height × channel_names.size()
    /// String attributes as written ("glint:azimuth_deg", …); on reading, every string
    /// attribute of the file.
    std::vector<std::pair<std::string, std::string>> metadata;
};

/// How a file stores its channels.
enum class PixelFormat : int { UInt8 = 0, UInt16 = 1, Half = 2, Float = 3 };

}  // namespace glint

namespace glint::detail {

/// Every entry returns None on success; otherwise the kind and a one-line `message`.
struct ImageIoTable {
    std::size_t table_size;  ///< sizeof(ImageIoTable) as the plugin was built
    /// `count` values in [0, 1] through a named map ("inferno", "viridis", "turbo", …) or,
    /// when `knot_count` > 0, through `knots` (knot_count × 3, linear between them) into
    /// `rgb` (3 × count).
    PluginErrorKind (*color_map)(const float* values, std::size_t count, const char* map_name,
                                 const float* knots, int knot_count, float* rgb,
                                 std::string& message) noexcept;
    PluginErrorKind (*draw_line)(const PixelView& image, int x0, int y0, int x1, int y1,
                                 const Rgb& colour, std::string& message) noexcept;
    PluginErrorKind (*draw_box)(const PixelView& image, int x0, int y0, int x1, int y1,
                                const Rgb& colour, bool fill, std::string& message) noexcept;
    /// `source` sampled onto `target`'s size, nearest pixel (no interpolation).
    PluginErrorKind (*resize_nearest)(const ConstPixelView& source, const PixelView& target,
                                      std::string& message) noexcept;
    /// PNG bytes of an 8-bit image at zlib level `level` with libpng row filter `filter`.
    PluginErrorKind (*encode_png)(const ConstPixelView& image, int level, int filter,
                                  std::string& bytes, std::string& message) noexcept;
    /// Writes `image` to `path` (format by extension) in `format`; `unassociated_alpha` marks
    /// straight (not premultiplied) alpha, as PNG stores it.
    PluginErrorKind (*write_file)(const std::filesystem::path& path, const FloatImage& image,
                                  PixelFormat format, bool unassociated_alpha,
                                  std::string& message) noexcept;
    /// Reads the first subimage of `path` as float channels with its names and metadata.
    PluginErrorKind (*read_file)(const std::filesystem::path& path, FloatImage& out,
                                 std::string& message) noexcept;
};

}  // namespace glint::detail

/// The plugin's one exported symbol; "v1" is the table's version.
#define GLINT_IMAGE_IO_ENTRY "glint_image_io_table_v1"
extern "C" const glint::detail::ImageIoTable* glint_image_io_table_v1();
