// Writing frames as images with OpenImageIO (image/image_ops.h, the image plugin): EXR (float,
// the numbers) or PNG (8/16-bit, for eyes), chosen by extension, written atomically, with the
// view in the metadata.
#pragma once

#include "render/frame.h"
#include "render/shade.h"
#include "render/view.h"

#include <filesystem>
#include <map>
#include <string>

namespace glint {

struct FrameImageOptions {
    ShadeOptions shade{};
    int png_bits = 8;  ///< 8 or 16
    /// Extra string metadata (device, mesh, …) written as "glint:<key>" attributes.
    std::map<std::string, std::string> metadata{};
};

/// Writes `frame` to `path`:
/// - .exr: float channels R, G, B, A (the shaded colour; alpha = coverage), and the raw
///   numbers N.x, N.y, N.z (normal), Z (depth, kNoDepth = inf), id (primitive id as float,
///   -1 where none; exact below 2^24 triangles). OpenEXR stores channels sorted by name:
///   readers must look them up by name, not position;
/// - .png: the shaded colour, RGBA.
/// Metadata: glint:azimuth_deg, glint:elevation_deg, glint:footprint, glint:zoom_index,
/// glint:mode, glint:normal_space, glint:projection, plus options.metadata.
/// \throw InputError unknown extension; IoError the write failed (OIIO's message included).
void write_frame_image(const std::filesystem::path& path, const Frame& frame, const View& view,
                       const FrameImageOptions& options = {});

/// Writes an already shaded image (.png or .exr) atomically. \throw InputError, IoError.
void write_rgba_image(const std::filesystem::path& path, const RgbaImage& image,
                      const std::map<std::string, std::string>& metadata = {}, int png_bits = 8);

}  // namespace glint
