// report.json's input checksums: SHA-256 as lowercase hex; a mesh file's taken from the bytes
// its loader parsed (no second read of a file that may be 50 MB, and no checksum of a file that
// changed after it was analysed).
#include "mesh/checksum.h"

#include "mesh/io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace glint {
namespace {

namespace fs = std::filesystem;

TEST(Checksum, Sha256OfKnownTexts) {
    // FIPS 180-2's examples.
    EXPECT_EQ(sha256_hex(std::string_view("abc")),
              "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(sha256_hex(std::string_view("")),
              "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Checksum, AMeshLoadCarriesTheChecksumOfTheBytesItParsed) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "checksum";
    fs::create_directories(dir);
    const fs::path file = dir / "tri.ply";
    std::ofstream(file) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                           "property float y\nproperty float z\nelement face 1\n"
                           "property list uchar int vertex_indices\nend_header\n"
                           "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const LoadedMesh loaded = load_mesh(file);
    EXPECT_EQ(loaded.report.sha256.size(), 64u);
    EXPECT_EQ(loaded.report.sha256, sha256_file(file));
    std::ofstream(file, std::ios::app) << "\n";  // the file changes after it was read
    EXPECT_NE(loaded.report.sha256, sha256_file(file));
}

}  // namespace
}  // namespace glint
