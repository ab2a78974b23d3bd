// Shared by the libFuzzer harnesses: the input goes to a temporary file (the readers take a
// path, and load_mesh detects the format from the bytes and the extension), then through the
// same entry point the CLI uses. A glint::Error is an expected refusal; anything else escaping
// (std::bad_alloc, std::length_error, a library's own exception), a sanitizer report, a crash,
// a hang or a run past libFuzzer's memory limit is a finding.
#pragma once

#include "mesh/error.h"
#include "mesh/io.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include <unistd.h>

namespace glint::fuzz {

/// A per-process file "<tmp>/glint-fuzz-<pid><ext>" holding `prefix` then the input.
inline std::filesystem::path write_input(std::string_view ext, std::string_view prefix,
                                         const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("glint-fuzz-" + std::to_string(::getpid()) + std::string(ext));
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) std::abort();
    std::fwrite(prefix.data(), 1, prefix.size(), f);
    if (size > 0) std::fwrite(data, 1, size, f);
    std::fclose(f);
    return path;
}

/// Runs `read` on the input written to a temporary file; glint errors are expected.
template <class Read>
int read_file(std::string_view ext, std::string_view prefix, const std::uint8_t* data,
              std::size_t size, Read read) {
    const auto path = write_input(ext, prefix, data, size);
    try {
        read(path);
    } catch (const glint::Error&) {
        // refused with a message: what hostile input should get
    }
    return 0;
}

/// load_mesh with a budget small enough for libFuzzer's memory limit (2 GB by default).
inline int load_mesh_input(std::string_view ext, std::string_view prefix, const std::uint8_t* data,
                           std::size_t size) {
    return read_file(ext, prefix, data, size, [](const std::filesystem::path& path) {
        (void)glint::load_mesh(
            path, glint::LoadOptions{.allow_points_only = true, .max_triangles = 1'000'000});
    });
}

}  // namespace glint::fuzz
