// Issue 23 items 8 and 11: mesh files are read, not mapped (a file that shrinks while it is
// read is an error, never a SIGBUS), and only regular files are read, opened without blocking
// (a FIFO used to block open() forever; /dev/zero said "file is empty").
#include "mesh/error.h"
#include "mesh/io.h"

#include "tests/mesh/load_error.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

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

// An ASCII PLY of `n` vertices and n - 2 triangles (a fan).
std::string big_ply(int n) {
    std::string s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(n) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(n - 2) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < n; ++i)
        s += std::to_string(i % 97) + " " + std::to_string(i / 97) + " " + std::to_string(i % 7) +
             "\n";
    for (int i = 1; i + 1 < n; ++i)
        s += "3 0 " + std::to_string(i) + " " + std::to_string(i + 1) + "\n";
    return s;
}

// The file is cut short while it is loaded, again and again: each load succeeds (it was read
// before the cut) or fails with a glint error; the process never dies of SIGBUS.
TEST(MeshFileKind, AFileCutWhileLoadedIsAnErrorNotACrash) {
    const fs::path path = dir("shrink") / "big.ply";
    const std::string text = big_ply(200000);
    for (int attempt = 0; attempt < 6; ++attempt) {
        {
            std::ofstream out(path, std::ios::binary | std::ios::trunc);
            out << text;
        }
        std::atomic<bool> started{false};
        std::thread cutter([&] {
            while (!started) std::this_thread::yield();
            std::this_thread::sleep_for(std::chrono::microseconds(200 * attempt));
            fs::resize_file(path, 64);
        });
        started = true;
        try {
            (void)load_mesh(path);
        } catch (const Error&) {
        }
        cutter.join();
    }
    SUCCEED();
}

}  // namespace
}  // namespace glint
