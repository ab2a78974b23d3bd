#include "report/output_folder.h"

#include "mesh/atomic_file.h"
#include "mesh/cancel.h"
#include "mesh/error.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;

// What a glint result's report.json holds that marks it as one (report/output_folder.cpp).
std::string glint_report(const std::string& run) { return "{\"glint_version\": \"" + run + "\"}"; }

fs::path base(const std::string& name) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "output_folder" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(OutputFolder, AppearsOnlyOnCommit) {
    const fs::path dir = base("commit");
    {
        OutputFolder out(dir / "atlas");
        write_file_atomically(out.file("report.json"), "{}");
        write_file_atomically(out.file("views/a.txt"), "x");
        EXPECT_FALSE(fs::exists(dir / "atlas"));
        out.commit();
    }
    EXPECT_TRUE(fs::exists(dir / "atlas" / "report.json"));
    EXPECT_TRUE(fs::exists(dir / "atlas" / "views" / "a.txt"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(OutputFolder, InterruptedRunLeavesNothingAndKeepsThePreviousResults) {
    const fs::path dir = base("interrupted");
    {
        OutputFolder first(dir / "atlas");
        write_file_atomically(first.file("report.json"), glint_report("old"));
        first.commit();
    }
    try {
        OutputFolder second(dir / "atlas", /*replace_existing=*/true);
        write_file_atomically(second.file("report.json"), "new, half done");
        throw IoError("simulated interruption");
    } catch (const IoError&) {
    }
    std::ifstream in(dir / "atlas" / "report.json");
    std::string text;
    std::getline(in, text);
    EXPECT_EQ(text, glint_report("old"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

// Issue 23 item 16: a signal that came while the last files were written stops the commit
// (it used to be swallowed, exit 0); the previous results stay, nothing staged is left.
TEST(OutputFolder, ASignalBeforeTheCommitStopsItAndKeepsThePreviousResults) {
    const fs::path dir = base("cancel_before_commit");
    {
        OutputFolder first(dir / "atlas");
        write_file_atomically(first.file("report.json"), glint_report("old"));
        first.commit();
    }
    {
        OutputFolder second(dir / "atlas", /*replace_existing=*/true);
        write_file_atomically(second.file("report.json"), "new");
        request_cancel(SIGTERM);
        EXPECT_THROW(second.commit(), Cancelled);
        reset_cancel();
    }
    std::ifstream in(dir / "atlas" / "report.json");
    std::string text;
    std::getline(in, text);
    EXPECT_EQ(text, glint_report("old"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

// The watchdog's last resort: the staging folder is listed while it exists and removed by
// remove_staged_now() (a step that never came back), and off the list once committed.
TEST(OutputFolder, ItsStagingFolderIsListedForTheWatchdogUntilCommitted) {
    const fs::path dir = base("staged_list");
    {
        OutputFolder stuck(dir / "stuck");
        write_file_atomically(stuck.file("views/a.txt"), "x");
        EXPECT_EQ(remove_staged_now(), 1u);
        EXPECT_FALSE(fs::exists(stuck.staging()));
    }
    OutputFolder done(dir / "done");
    write_file_atomically(done.file("report.json"), "{}");
    done.commit();
    EXPECT_EQ(remove_staged_now(), 0u);
    EXPECT_TRUE(fs::exists(dir / "done" / "report.json"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(OutputFolder, RefusesAnExistingFolderUnlessAllowedToReplaceIt) {
    const fs::path dir = base("refuse");
    {
        OutputFolder first(dir / "atlas");
        write_file_atomically(first.file("report.json"), "one");
        first.commit();
    }
    try {
        OutputFolder second(dir / "atlas");
        FAIL() << "an existing output folder was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("exists; give --force"), std::string::npos)
            << e.what();
    }
    // Nothing was staged beside it.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(OutputFolder, ReplacesAnEarlierRunOnCommit) {
    const fs::path dir = base("replace");
    for (const char* content : {"one", "two"}) {
        OutputFolder out(dir / "atlas", /*replace_existing=*/true);
        write_file_atomically(out.file("report.json"), glint_report(content));
        out.commit();
    }
    std::ifstream in(dir / "atlas" / "report.json");
    std::string text;
    std::getline(in, text);
    EXPECT_EQ(text, glint_report("two"));
}

TEST(OutputFolder, MissingParentIsAnIoErrorNamingIt) {
    const fs::path dir = base("missing");
    try {
        OutputFolder out(dir / "no" / "such" / "atlas");
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
    }
}

TEST(OutputFolder, RefusesAFileInPlaceOfTheFolder) {
    const fs::path dir = base("file");
    write_file_atomically(dir / "atlas", "a file");
    EXPECT_THROW(OutputFolder(dir / "atlas"), InputError);
}

// A file and its folder, as a user makes them.
void write_new(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    std::string text;
    std::getline(in, text);
    return text;
}

std::size_t entries(const fs::path& dir) {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(dir), fs::directory_iterator{}));
}

// Item 1 of issue 23: `-o d --force` where d holds the inputs deleted them.
TEST(OutputFolder, RefusesAFolderHoldingAnInputBeforeMakingAnything) {
    const fs::path dir = base("holds_input");
    write_new(dir / "d" / "ref.ply", "input");
    protect_input(dir / "d" / "ref.ply");
    try {
        OutputFolder out(dir / "d", /*replace_existing=*/true);
        FAIL() << "an output folder holding an input was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("contains the input"), std::string::npos) << e.what();
    }
    EXPECT_EQ(read_text(dir / "d" / "ref.ply"), "input");
    EXPECT_EQ(entries(dir), 1u);  // nothing staged beside it
}

// Item 4: without --force a folder that appeared during the run is kept, the run refused.
TEST(OutputFolder, KeepsATargetThatAppearedDuringTheRun) {
    const fs::path dir = base("appeared");
    OutputFolder out(dir / "atlas");
    write_file_atomically(out.file("report.json"), "mine");
    fs::create_directories(dir / "atlas");
    write_file_atomically(dir / "atlas" / "report.json", "theirs");
    try {
        out.commit();
        FAIL() << "commit replaced a folder that appeared during the run";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("appeared during the run"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(read_text(dir / "atlas" / "report.json"), "theirs");
}

// Item 4 with an empty folder made by another program: still refused (renameat2 NOREPLACE).
TEST(OutputFolder, KeepsAnEmptyTargetThatAppearedDuringTheRun) {
    const fs::path dir = base("appeared_empty");
    OutputFolder out(dir / "atlas");
    write_file_atomically(out.file("report.json"), "mine");
    fs::create_directories(dir / "atlas");
    EXPECT_THROW(out.commit(), InputError);
    EXPECT_TRUE(fs::is_directory(dir / "atlas"));
}

// Item 5: a user's folder named like a staging folder is never taken over or deleted.
TEST(OutputFolder, NeverTakesOverAUserFolderNamedLikeItsStaging) {
    const fs::path dir = base("user_partial");
    const fs::path user = dir / ("atlas.partial-" + std::to_string(::getpid()));
    write_new(user / "notes.txt", "precious");
    {
        OutputFolder out(dir / "atlas");
        EXPECT_NE(out.staging().parent_path(), user);
        write_file_atomically(out.file("report.json"), "new");
        out.commit();
    }
    EXPECT_EQ(read_text(user / "notes.txt"), "precious");
    EXPECT_EQ(read_text(dir / "atlas" / "report.json"), "new");
}

// Item 5: leftovers of killed runs (marked, process gone) are removed; unmarked ones stay.
TEST(OutputFolder, RemovesTheMarkedLeftoversOfKilledRunsOnly) {
    const fs::path dir = base("leftovers");
    const pid_t child = ::fork();
    if (child == 0) {
        OutputFolder out(dir / "atlas");
        write_file_atomically(out.file("report.json"), "half");
        ::_exit(0);  // killed: no destructor runs
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    const fs::path left = dir / ("atlas.partial-" + std::to_string(child));
    ASSERT_TRUE(fs::exists(left / kStagingMarker));
    const fs::path unmarked = dir / "atlas.partial-1";
    write_new(unmarked / "notes.txt", "user's");
    {
        OutputFolder out(dir / "atlas");
        out.commit();
    }
    EXPECT_FALSE(fs::exists(left));
    EXPECT_EQ(read_text(unmarked / "notes.txt"), "user's");
    EXPECT_FALSE(fs::exists(dir / "atlas" / kStagingMarker));
}

// A run killed between making its staging wrapper and writing the marker leaves an empty,
// unmarked "<out>.partial-<pid>": removed once that pid is gone. An unmarked one holding
// anything, or named for a live process, stays.
TEST(OutputFolder, RemovesTheEmptyWrapperOfARunKilledBeforeItsMarker) {
    const fs::path dir = base("unmarked_leftovers");
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    const fs::path empty = dir / ("atlas.partial-" + std::to_string(child));
    const fs::path empty_second = dir / ("atlas.partial-" + std::to_string(child) + "-1");
    const fs::path kept = dir / ("atlas.partial-" + std::to_string(child) + "-2");
    const fs::path alive = dir / ("atlas.partial-" + std::to_string(::getppid()));
    const fs::path not_a_pid = dir / "atlas.partial-x1";
    for (const fs::path& p : {empty, empty_second, alive, not_a_pid}) fs::create_directories(p);
    write_new(kept / "notes.txt", "user's");
    {
        OutputFolder out(dir / "atlas");
        out.commit();
    }
    EXPECT_FALSE(fs::exists(empty));
    EXPECT_FALSE(fs::exists(empty_second));
    EXPECT_EQ(read_text(kept / "notes.txt"), "user's");
    EXPECT_TRUE(fs::is_directory(alive));
    EXPECT_TRUE(fs::is_directory(not_a_pid));
}

// Item 5: --force replaces with one exchange: the old folder is whole or the new one is.
TEST(OutputFolder, ReplacingLeavesNoStagingOrAsideFolders) {
    const fs::path dir = base("exchange");
    for (const char* content : {"one", "two"}) {
        OutputFolder out(dir / "atlas", /*replace_existing=*/true);
        write_file_atomically(out.file("report.json"), glint_report(content));
        out.commit();
    }
    EXPECT_EQ(read_text(dir / "atlas" / "report.json"), glint_report("two"));
    EXPECT_EQ(entries(dir), 1u);
}

// Issue 52: `-o . --force` or `-o .. --force` replaced any folder that held no input. A folder
// glint did not write is never replaced, with --force or without; an empty one or an earlier
// result (its report.json names the glint version) is.
TEST(OutputFolder, NeverReplacesAFolderGlintDidNotWrite) {
    const fs::path dir = base("foreign");
    write_new(dir / "home" / "thesis.tex", "years of work");
    write_new(dir / "home" / "report.json", "{\"author\": \"me\"}");  // a report, not glint's
    try {
        OutputFolder out(dir / "home", /*replace_existing=*/true);
        FAIL() << "a folder glint did not write was accepted for replacing";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("holds files glint did not write"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(read_text(dir / "home" / "thesis.tex"), "years of work");
    EXPECT_EQ(entries(dir), 1u);  // nothing staged beside it
    // An empty folder and an earlier result are replaced.
    fs::create_directories(dir / "empty");
    for (const char* target : {"empty", "result"}) {
        if (std::string(target) == "result")
            write_new(dir / "result" / "report.json",
                      "{\"device\": {}, " + glint_report("0.9").substr(1));
        OutputFolder out(dir / target, /*replace_existing=*/true);
        write_file_atomically(out.file("report.json"), glint_report("new"));
        out.commit();
        EXPECT_EQ(read_text(dir / target / "report.json"), glint_report("new")) << target;
    }
}

// The folder became someone else's while the run worked: its commit refuses and keeps it.
TEST(OutputFolder, ForceRefusesAtCommitAFolderThatBecameTheUsers) {
    const fs::path dir = base("became_foreign");
    OutputFolder out(dir / "atlas", /*replace_existing=*/true);
    write_file_atomically(out.file("report.json"), glint_report("mine"));
    write_new(dir / "atlas" / "notes.txt", "the user's");
    EXPECT_THROW(out.commit(), InputError);
    EXPECT_EQ(read_text(dir / "atlas" / "notes.txt"), "the user's");
}

// Issue 52: a file read after the folder was made (a ROI mask read during the sweep, a slice,
// a glTF buffer) is an input by commit time: the results never replace the folder holding it.
TEST(OutputFolder, CommitRefusesAFolderHoldingAFileReadDuringTheRun) {
    const fs::path dir = base("read_later");
    {
        OutputFolder first(dir / "m");
        write_file_atomically(first.file("report.json"), glint_report("old"));
        first.commit();
    }
    write_new(dir / "m" / "m.ply", "the mask");
    OutputFolder out(dir / "m", /*replace_existing=*/true);
    write_file_atomically(out.file("report.json"), glint_report("new"));
    protect_input(dir / "m" / "m.ply");  // as the mask's loader does when it reads it
    try {
        out.commit();
        FAIL() << "the commit replaced a folder holding an input";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("contains the input"), std::string::npos) << e.what();
    }
    EXPECT_EQ(read_text(dir / "m" / "m.ply"), "the mask");
    EXPECT_EQ(read_text(dir / "m" / "report.json"), glint_report("old"));
}

// A symbolic link at the output's place is named at once, not after the whole analysis.
TEST(OutputFolder, RefusesASymbolicLinkAtItsPlace) {
    const fs::path dir = base("symlink");
    fs::create_symlink(dir / "nowhere", dir / "out");
    EXPECT_THROW(OutputFolder(dir / "out", /*replace_existing=*/true), InputError);
    EXPECT_THROW(OutputFolder(dir / "out"), InputError);
    EXPECT_TRUE(fs::is_symlink(dir / "out"));
}

}  // namespace
}  // namespace glint
