// Issue 23 item 18: an input behind a folder this user may not enter is named by that folder,
// as an I/O problem (exit 3), not as "file not found" (exit 2).
#include "mesh/input_path.h"

#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/small_file.h"
#include "tests/mesh/unprivileged.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;

struct BarredFolder {
    fs::path root = test::open_temp_folder("input_path");
    fs::path barred = root / "barred";
    BarredFolder() {
        fs::create_directories(barred / "inner");
        std::ofstream(barred / "inner" / "a.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        fs::permissions(barred, fs::perms::none);
    }
    ~BarredFolder() {
        std::error_code ec;
        fs::permissions(barred, fs::perms::owner_all, ec);
        fs::remove_all(root, ec);
    }
};

std::string reach_name(PathReach r) {
    switch (r) {
        case PathReach::Reachable: return "reachable";
        case PathReach::Missing: return "missing";
        case PathReach::Denied: return "denied";
        case PathReach::Failed: return "failed";
    }
    return "?";
}

TEST(InputPath, AFolderThisUserMayNotEnterIsNamedNotMissing) {
    const BarredFolder f;
    const fs::path file = f.barred / "inner" / "a.obj";
    const std::string seen = test::as_unprivileged([&] {
        const PathCheck c = check_path(file);
        return reach_name(c.reach) + "|" + c.reason;
    });
    EXPECT_EQ(seen, "denied|folder \"" + f.barred.string() +
                        "\" may not be entered by this user (permission denied); expected a "
                        "path this user can reach");
}

TEST(InputPath, MissingAndReachablePathsAreToldApart) {
    const fs::path root = test::open_temp_folder("input_path_plain");
    std::ofstream(root / "here.txt") << "x";
    EXPECT_EQ(check_path(root / "here.txt").reach, PathReach::Reachable);
    EXPECT_EQ(check_path(root).reach, PathReach::Reachable);
    EXPECT_EQ(check_path(root / "gone.txt").reach, PathReach::Missing);
    EXPECT_EQ(check_path(root / "here.txt" / "below").reach, PathReach::Missing);  // ENOTDIR
    EXPECT_TRUE(reachable_input(root / "here.txt", "mesh"));
    EXPECT_FALSE(reachable_input(root / "gone.txt", "mesh"));
    fs::create_symlink("loop", root / "loop");
    EXPECT_EQ(check_path(root / "loop").reach, PathReach::Failed);  // ELOOP
    EXPECT_THROW((void)reachable_input(root / "loop", "mesh"), IoError);
    fs::remove_all(root);
}

TEST(InputPath, ReadersSayWhichFolderBarsTheWayAsAnIoError) {
    const BarredFolder f;
    const fs::path file = f.barred / "inner" / "a.obj";
    const std::string barred = "folder \"" + f.barred.string() + "\" may not be entered";
    const std::string mesh = test::as_unprivileged([&]() -> std::string {
        try {
            (void)load_mesh(file);
        } catch (const IoError& e) {
            return std::string("IoError: ") + e.what();
        }
        return "loaded";
    });
    EXPECT_EQ(mesh.rfind("IoError: mesh \"" + file.string() + "\": " + barred, 0), 0u) << mesh;
    const std::string small = test::as_unprivileged([&]() -> std::string {
        try {
            (void)read_small_file(file, "fit");
        } catch (const IoError& e) {
            return std::string("IoError: ") + e.what();
        }
        return "read";
    });
    EXPECT_EQ(small.rfind("IoError: fit \"" + file.string() + "\": " + barred, 0), 0u) << small;
}

}  // namespace
}  // namespace glint
