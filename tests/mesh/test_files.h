// Files the mesh tests write: one folder per test file under GLINT_TEST_OUTPUT_DIR (a CMake
// compile definition, never the working directory).
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace glint::test {

/// GLINT_TEST_OUTPUT_DIR/<suite>, created on first use.
inline std::filesystem::path output_dir(const std::string& suite) {
    const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / suite;
    std::filesystem::create_directories(dir);
    return dir;
}

/// GLINT_TEST_OUTPUT_DIR/<suite>/<name>, emptied: each test starts from a folder of its own.
inline std::filesystem::path fresh_dir(const std::string& suite, const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / suite / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Writes `bytes` verbatim to dir/name and returns the path.
inline std::filesystem::path write_bytes(const std::filesystem::path& dir, const std::string& name,
                                         const std::string& bytes) {
    const std::filesystem::path path = dir / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

}  // namespace glint::test
