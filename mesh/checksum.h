// SHA-256 checksums of inputs, as report.json records them (lowercase hex, 64 characters).
#pragma once

#include <filesystem>
#include <span>
#include <string>

namespace glint {

/// The SHA-256 of `bytes`.
[[nodiscard]] std::string sha256_hex(std::span<const char> bytes);

/// The SHA-256 of the file at `path`, read now. \throw IoError when it cannot be read.
[[nodiscard]] std::string sha256_file(const std::filesystem::path& path);

}  // namespace glint
