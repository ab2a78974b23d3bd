#include "report/output_folder.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

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
        write_file_atomically(first.file("report.json"), "old");
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
    EXPECT_EQ(text, "old");
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
        write_file_atomically(out.file("report.json"), content);
        out.commit();
    }
    std::ifstream in(dir / "atlas" / "report.json");
    std::string text;
    std::getline(in, text);
    EXPECT_EQ(text, "two");
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

}  // namespace
}  // namespace glint
