// Issue 23 item 11: only regular mesh files are read, opened without blocking (a FIFO used to
// block open() forever; /dev/zero said "file is empty").
#include "mesh/error.h"
#include "mesh/io.h"

#include "tests/mesh/load_error.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <filesystem>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::load_error;

fs::path dir(const std::string& name) {
    const fs::path d = fs::path(GLINT_TEST_OUTPUT_DIR) / "file_kind" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

TEST(MeshFileKind, RefusesAFifoWithoutBlocking) {
    const fs::path fifo = dir("fifo") / "mesh.ply";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_CONTAINS(load_error<InputError>(fifo), "is a FIFO, expected a regular mesh file");
}

TEST(MeshFileKind, RefusesACharacterDevice) {
    EXPECT_CONTAINS(load_error<InputError>("/dev/zero"),
                    "\"/dev/zero\": is a character device, expected a regular mesh file");
}

}  // namespace
}  // namespace glint
