// Writing a file so that it is either complete or absent: write to a temporary name in the
// same folder, flush, then rename over the target.
#pragma once

#include "mesh/error.h"

#include <filesystem>
#include <functional>
#include <ostream>
#include <span>
#include <string_view>

namespace glint {

/// Calls `write` with a binary stream on a temporary file next to `path`, then renames it to
/// `path`. On any failure (exception from `write`, stream error, rename error) the temporary
/// file is removed and IoError names the path. Refuses to write over a file listed in
/// `protected_inputs` (InputError): inputs are never overwritten.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write);

/// Same guarantee for writers that need a file name rather than a stream (image libraries
/// choose the format by extension): `write` receives a temporary path in the same folder with
/// the same extension, and must create that file; it is then renamed to `path`.
void write_atomically_to_path(const std::filesystem::path& path,
                              const std::function<void(const std::filesystem::path& temp)>& write);

/// Registers a path as an input of this process: write_atomically refuses to replace it.
void protect_input(const std::filesystem::path& path);

/// `error` with every mention of `staged` (a temporary or staging name the user never sees)
/// replaced by `target`, the name the user gave.
[[nodiscard]] IoError naming_target(const IoError& error, const std::filesystem::path& staged,
                                    const std::filesystem::path& target);

/// Convenience: writes bytes/text atomically.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace glint
