#include "mesh/atomic_file.h"

#include "mesh/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "atomic" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string read_all(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(WriteAtomically, WritesCompleteFileAndLeavesNoTemporary) {
    const auto dir = fresh_dir("ok");
    write_file_atomically(dir / "a.txt", "hello");
    EXPECT_EQ(read_all(dir / "a.txt"), "hello");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(WriteAtomically, FailureMidwayKeepsTheOldFileAndRemovesTheTemporary) {
    const auto dir = fresh_dir("fail");
    write_file_atomically(dir / "a.txt", "old");
    EXPECT_THROW(write_atomically(dir / "a.txt",
                                  [](std::ostream& out) {
                                      out << "half";
                                      throw IoError("simulated failure");
                                  }),
                 IoError);
    EXPECT_EQ(read_all(dir / "a.txt"), "old");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(WriteAtomically, RefusesToOverwriteAnInput) {
    const auto dir = fresh_dir("input");
    write_file_atomically(dir / "in.ply", "data");
    protect_input(dir / "in.ply");
    try {
        write_file_atomically(dir / "." / "in.ply", "other");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("in.ply"), std::string::npos);
    }
    EXPECT_EQ(read_all(dir / "in.ply"), "data");
}

TEST(WriteAtomically, MissingFolderIsAnIoErrorNamingThePath) {
    const auto dir = fresh_dir("missing");
    try {
        write_file_atomically(dir / "nope" / "a.txt", "x");
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos);
    }
}

}  // namespace
}  // namespace glint
