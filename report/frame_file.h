// Reading a frame back from the EXR that `glint render` writes (render/image_io.h):
// channels N.x N.y N.z (normal), Z (depth), id (primitive id as float, −1 = none) and A
// (coverage). Used by `glint compare` on frames rendered earlier.
#pragma once

#include "render/frame.h"

#include <filesystem>

namespace glint {

/// \throw IoError unreadable file; InputError not a glint frame (missing channels).
[[nodiscard]] Frame read_frame_exr(const std::filesystem::path& path);

}  // namespace glint
