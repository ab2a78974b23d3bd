#include "mesh/atomic_file.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/file_set.h"
#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) { return test::fresh_dir("atomic", name); }

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

// Issue 23 item 16: a signal during the writing stops before the rename; the old file stays.
TEST(WriteAtomically, ASignalDuringTheWritingKeepsTheOldFile) {
    const auto dir = fresh_dir("cancelled");
    write_file_atomically(dir / "f.txt", "old");
    EXPECT_THROW(write_atomically(dir / "f.txt",
                                  [](std::ostream& out) {
                                      out << "new";
                                      request_cancel(SIGINT);
                                  }),
                 Cancelled);
    reset_cancel();
    EXPECT_EQ(read_all(dir / "f.txt"), "old");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

// A set of files (a mesh and its sidecar) stopped by a signal: none of them appears.
TEST(FileSet, ASignalBeforeTheCommitLeavesNoneOfTheSet) {
    const auto dir = fresh_dir("set_cancelled");
    {
        FileSet set;
        set.add(dir / "p.ply", "ply");
        set.add(dir / "p.ply.json", "{}");
        request_cancel(SIGTERM);
        EXPECT_THROW(set.commit(), Cancelled);
        reset_cancel();
    }
    EXPECT_TRUE(fs::is_empty(dir));
}

// Temporaries are listed for the watchdog while they exist, and off the list once renamed.
TEST(FileSet, ItsTemporariesAreListedForTheWatchdogUntilCommitted) {
    const auto dir = fresh_dir("set_listed");
    FileSet set;
    set.add(dir / "a.txt", "a");
    set.add(dir / "b.txt", "b");
    EXPECT_EQ(remove_staged_now(), 2u);
    EXPECT_TRUE(fs::is_empty(dir));
    FileSet again;
    again.add(dir / "a.txt", "a");
    again.commit();
    EXPECT_EQ(remove_staged_now(), 0u);
    EXPECT_EQ(read_all(dir / "a.txt"), "a");
}

// A writer's error names the file the user asked for, not the temporary it was handed (a full
// disk said "cannot write \".p.tmp-13939-0.ply\"" for p.ply).
TEST(WriteAtomically, AWritersErrorNamesTheTargetNotTheTemporary) {
    const auto dir = fresh_dir("error_names_target");
    try {
        write_atomically_to_path(dir / "p.ply", [](const fs::path& temp) {
            throw IoError("cannot write \"" + temp.string() + "\": write failed (disk full?)");
        });
        FAIL() << "the writer's error was swallowed";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "cannot write \"" + (dir / "p.ply").string() + "\": write failed (disk full?)");
    }
    EXPECT_TRUE(fs::is_empty(dir));
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
