// Turning a Frame into pixels a person looks at, or the paper's variants of the normal
// frame: colour modes computed from the float normals, identical for both backends.
//
//   Normal      rgb = 0.5·n + 0.5 (the paper's normal colour), float
//   Paper8      the same quantised to 8 bits (round(255·c)/255), as the paper saved it
//   Reflection  the paper's light-reflection variant: grey = max(0, n·l), one fixed light l
//   Zebra       reflection lines: stripes of the reflected view vector's angle about the
//               light axis (surface-quality check: kinks and bumps bend the stripes)
//   Depth       grey = 1 at the nearest covered depth of the frame, 0 at the farthest
// Uncovered pixels are black with alpha 0; alpha = coverage.
#pragma once

#include "mesh/mesh.h"
#include "render/frame.h"
#include "render/view.h"

#include <string>
#include <vector>

namespace glint {

enum class ShadeMode { Normal, Reflection, Zebra, Paper8, Depth };

/// "normal" / "reflection" / "zebra" / "paper8" / "depth". \throw InputError.
[[nodiscard]] ShadeMode parse_shade_mode(const std::string& text);
[[nodiscard]] std::string to_string(ShadeMode mode);

struct ShadeOptions {
    ShadeMode mode = ShadeMode::Normal;
    /// Light direction (towards the light) in camera coordinates: x right, y up, z towards
    /// the viewer. Default: from the upper left behind the viewer, the paper's fixed light.
    Vec3d light_in_camera{-0.3, 0.4, 0.866};
    double zebra_stripes = 12.0;  ///< Zebra: number of stripe pairs over 180°
};

/// RGBA float image, row-major, 4 channels, row 0 at the top.
struct RgbaImage {
    int width = 0;
    int height = 0;
    std::vector<float> pixels;  ///< 4 per pixel
};

/// Colours a frame (normals in either space; the view gives the camera for View/World
/// conversion and for reflection / zebra).
[[nodiscard]] RgbaImage shade(const Frame& frame, const View& view, const ShadeOptions& options);

/// World-space normal of a frame's pixel converted to camera coordinates (or returned as is
/// when the frame is already in view space).
[[nodiscard]] Vec3f normal_in_camera(const Frame& frame, const View& view, std::size_t pixel);

}  // namespace glint
