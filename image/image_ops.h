// What glint does to pictures and image files through OpenImageIO, on its own memory
// (image/canvas.h): colour maps, lines and boxes, resampling, PNG encoding, reading and
// writing EXR/PNG files. Each call goes to the image plugin (libglint_image_io.so), opened on
// the first call; a missing plugin is an IoError (exit 3) naming the package to install.
#pragma once

#include "image/canvas.h"
#include "image/plugin/image_io_abi.h"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// Makes sure pictures can be drawn before a long run starts: throws IoError (exit 3) naming
/// the package to install when the image plugin is missing, and opens it on a background
/// thread, so loading OpenImageIO overlaps the run's own work.
void preload_image_io();

/// Values in [0, 1] through a named OpenImageIO colour map ("inferno", "viridis", "turbo",
/// "magma", "plasma", "blue-red", "spectrum", "heat"): 3 floats per value.
/// \throw InputError an unknown map name.
[[nodiscard]] std::vector<float> color_map(std::span<const float> values, std::string_view map);

/// Values in [0, 1] through a map given by its knots (3 floats each, evenly spaced, linear
/// between them): 3 floats per value.
[[nodiscard]] std::vector<float> color_map(std::span<const float> values,
                                           std::span<const float> knots);

/// A one-pixel line from (x0, y0) to (x1, y1), clipped to the canvas (ImageBufAlgo::render_line).
void draw_line(Canvas& canvas, int x0, int y0, int x1, int y1, const Rgb& colour);

/// A box from (x0, y0) to (x1, y1) inclusive, filled or outlined (ImageBufAlgo::render_box).
void draw_box(Canvas& canvas, int x0, int y0, int x1, int y1, const Rgb& colour, bool fill);

/// `source` scaled to width × height, nearest pixel (blocks stay sharp).
[[nodiscard]] Canvas resize_nearest(const Canvas& source, int width, int height);

/// The canvas as PNG bytes (8 bits per channel). zlib level 1 with the "sub" row filter:
/// a 674 × 414 view picture encoded in 6.7 ms instead of 19.8 ms (libpng's defaults), the
/// file 23 % larger; the pixels are the same. \throw IoError.
[[nodiscard]] std::string encode_png(const Canvas& canvas);

/// Writes `image` to `path` (the format by extension: .png, .exr, …) in `format`, in place:
/// callers write to a temporary name and rename (mesh/atomic_file.h). \throw IoError.
void write_image_file(const std::filesystem::path& path, const FloatImage& image,
                      PixelFormat format, bool unassociated_alpha = false);

/// The first subimage of `path` as float channels, with its names and string metadata.
/// \throw InputError not an image file; IoError a read that failed midway.
[[nodiscard]] FloatImage read_image_file(const std::filesystem::path& path);

}  // namespace glint
