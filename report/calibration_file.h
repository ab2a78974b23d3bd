// calibration.json (analysis/calibrate.h's Calibration as a file): what `glint calibrate`
// writes and `glint sweep --calibration` reads.
#pragma once

#include "analysis/calibrate.h"

#include <filesystem>
#include <string>

namespace glint {

/// The calibration as calibration.json's text.
[[nodiscard]] std::string to_json(const Calibration& calibration);

/// \throw IoError, InputError (not a calibration, or one that found no footprint).
[[nodiscard]] Calibration read_calibration(const std::filesystem::path& path);

}  // namespace glint
