// Whole small input files (fit, landmarks, calibration, scenario, views, masks, pose files)
// read the one safe way (issue 23, items 10, 11 and 18): only a regular file, opened without
// blocking (a FIFO never hangs the run), a folder or a device named as such rather than an
// "internal error" from a stream, and a size cap read before any byte is.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace glint {

/// The bytes of `path`, at most `max_bytes`. `what` names the file in messages ("fit",
/// "landmarks", "scenario"): `fit "x.json": is a folder, expected a file`.
/// \throw IoError when it is missing or cannot be read; InputError when it is not a regular
/// file, is larger than `max_bytes`, or changed size while it was read.
[[nodiscard]] std::string read_small_file(const std::filesystem::path& path,
                                          const std::string& what,
                                          std::size_t max_bytes = std::size_t{64} << 20);

}  // namespace glint
