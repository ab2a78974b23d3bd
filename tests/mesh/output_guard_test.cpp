#include "mesh/output_guard.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/file_set.h"
#include "tests/mesh/unprivileged.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path base(const std::string& name) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "output_guard" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string refusal(const fs::path& output, std::initializer_list<fs::path> inputs) {
    try {
        guard_outputs({output}, inputs);
    } catch (const InputError& e) {
        return e.what();
    }
    return {};
}

TEST(OutputGuard, RefusesAnOutputThatIsContainsOrLiesInsideAnInput) {
    const fs::path dir = base("relations");
    fs::create_directories(dir / "d");
    write_file_atomically(dir / "d" / "ref.ply", "x");
    fs::create_directories(dir / "dcm");
    EXPECT_NE(refusal(dir / "d" / "ref.ply", {dir / "d" / "ref.ply"}).find("\" is the input"),
              std::string::npos);
    EXPECT_NE(refusal(dir / "d", {dir / "d" / "ref.ply"}).find("contains the input"),
              std::string::npos);
    EXPECT_NE(refusal(dir / "d" / ".." / "d" / "", {dir / "d" / "ref.ply"}).find("contains"),
              std::string::npos);
    EXPECT_NE(refusal(dir / "dcm" / "out.ply", {dir / "dcm"}).find("lies inside the input"),
              std::string::npos);
    EXPECT_EQ(refusal(dir / "out", {dir / "d" / "ref.ply"}), "");
}

std::string folder_refusal(const fs::path& output, OutputParent parent) {
    try {
        check_output_folder(output, parent);
    } catch (const InputError& e) {
        return e.what();
    }
    return {};
}

TEST(OutputGuard, RefusesAMissingFolderNamingOutputFolderFoundAndExpected) {
    const fs::path dir = base("missing_folder");
    const fs::path out = dir / "missing_dir" / "x.ply";
    const std::string why = folder_refusal(out, OutputParent::MustExist);
    EXPECT_EQ(why, "output \"" + out.string() + "\": folder \"" + (dir / "missing_dir").string() +
                       "\" does not exist; expected an existing folder to write into (make it "
                       "first) (nothing was written)");
    EXPECT_EQ(folder_refusal(dir / "x.ply", OutputParent::MustExist), "");
    EXPECT_EQ(folder_refusal(dir / "atlas" / "", OutputParent::MustExist), "");  // "atlas/"
    EXPECT_FALSE(fs::exists(dir / "missing_dir"));
}

TEST(OutputGuard, AFolderTheCommandMakesNeedsAWritableFolderAboveIt) {
    const fs::path dir = base("made_folder");
    EXPECT_EQ(folder_refusal(dir / "a" / "b" / "x", OutputParent::MayBeCreated), "");
    EXPECT_FALSE(fs::exists(dir / "a"));  // checked, not made
    write_file_atomically(dir / "f", "x");
    EXPECT_NE(folder_refusal(dir / "f" / "a" / "x", OutputParent::MayBeCreated)
                  .find("cannot be made: \"" + (dir / "f").string() + "\" is a file, not a folder"),
              std::string::npos);
    EXPECT_NE(folder_refusal(dir / "f" / "x", OutputParent::MustExist)
                  .find("\"" + (dir / "f").string() + "\" is a file, not a folder"),
              std::string::npos);
}

// Root may write anywhere: as root the check runs as user nobody (tests/mesh/unprivileged.h).
TEST(OutputGuard, RefusesAFolderThatIsNotWritable) {
    const fs::path dir = test::open_temp_folder("read_only");
    fs::create_directories(dir / "ro");
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec |
                                    fs::perms::others_read | fs::perms::others_exec);
    const std::string why = test::as_unprivileged(
        [&] { return folder_refusal(dir / "ro" / "x.ply", OutputParent::MustExist); });
    const std::string made = test::as_unprivileged(
        [&] { return folder_refusal(dir / "ro" / "new" / "x", OutputParent::MayBeCreated); });
    fs::permissions(dir / "ro", fs::perms::owner_all);
    fs::remove_all(dir);
    EXPECT_NE(why.find("folder \"" + (dir / "ro").string() + "\" is not writable"),
              std::string::npos);
    EXPECT_NE(made.find("\" is not writable"), std::string::npos);
}

TEST(OutputGuard, GuardOutputsChecksEachOutputsFolder) {
    const fs::path dir = base("guard_folders");
    EXPECT_NE(refusal(dir / "missing_dir" / "x.ply", {}).find("does not exist"), std::string::npos);
    EXPECT_THROW(guard_outputs({dir / "ok.ply", dir / "no" / "x.json"}, {}), InputError);
    EXPECT_NO_THROW(guard_outputs({dir / "no" / "x"}, {}, OutputParent::MayBeCreated));
}

TEST(OutputGuard, FollowsSymbolicLinksAndHardLinks) {
    const fs::path dir = base("links");
    write_file_atomically(dir / "a.json", "{}");
    fs::create_hard_link(dir / "a.json", dir / "b.json");
    fs::create_directory_symlink(dir, dir / "link");
    EXPECT_NE(refusal(dir / "b.json", {dir / "a.json"}), "");
    EXPECT_NE(refusal(dir / "link" / "a.json", {dir / "a.json"}), "");
}

// Item 3 of issue 23: volume-edit v.mhd overwrote its raw data file.
TEST(OutputGuard, AHeaderInputProtectsItsDataFile) {
    const fs::path dir = base("mhd");
    write_file_atomically(dir / "v.mhd", "ObjectType = Image\nElementDataFile = w.raw\n");
    write_file_atomically(dir / "w.raw", "voxels");
    const auto files = input_files(dir / "v.mhd");
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[1], dir / "w.raw");
    // w.mhd writes w.raw: the input's data.
    EXPECT_NE(refusal(dir / "w.mhd", {dir / "v.mhd"}).find("w.raw"), std::string::npos);
}

// Issue 52: data named by a slice pattern or a LIST was not followed: `-o slices --force`
// deleted all 113 slices of CThead.mhd, and volume-edit -o s1.mhd overwrote the slice s1.raw.
TEST(OutputGuard, AHeaderInputProtectsEverySliceItsPatternOrListNames) {
    const fs::path dir = base("patterns");
    fs::create_directories(dir / "slices");
    fs::create_directories(dir / "hdr");
    write_file_atomically(dir / "hdr" / "ct.mhd",
                          "NDims = 3\nElementDataFile = ../slices/CThead.%d 1 113 1\n");
    auto files = input_files(dir / "hdr" / "ct.mhd");
    ASSERT_EQ(files.size(), 114u);
    EXPECT_EQ(files[1], dir / "hdr" / "../slices/CThead.1");
    EXPECT_EQ(files[113], dir / "hdr" / "../slices/CThead.113");
    EXPECT_NE(refusal(dir / "slices", {dir / "hdr" / "ct.mhd"}).find("contains the input"),
              std::string::npos);
    // Zero-padded, with a step.
    write_file_atomically(dir / "p.mhd", "ElementDataFile = s%03d.raw 2 6 2\n");
    files = input_files(dir / "p.mhd");
    ASSERT_EQ(files.size(), 4u);
    EXPECT_EQ(files[1], dir / "s002.raw");
    EXPECT_EQ(files[3], dir / "s006.raw");
    // A LIST: the header's following lines.
    write_file_atomically(dir / "l.mhd", "NDims = 3\nElementDataFile = LIST 2D\na.raw\nb.raw\n");
    files = input_files(dir / "l.mhd");
    ASSERT_EQ(files.size(), 3u);
    EXPECT_EQ(files[2], dir / "b.raw");
    // NRRD: a pattern with its sub-dimension, and a LIST.
    write_file_atomically(dir / "n.nhdr",
                          "NRRD0004\ntype: short\ndata file: ../sl/s%d.raw 1 3 1 2\n");
    files = input_files(dir / "n.nhdr");
    ASSERT_EQ(files.size(), 4u);
    EXPECT_EQ(files[3], dir / "../sl/s3.raw");
    write_file_atomically(dir / "m.nhdr", "NRRD0004\ndata file: LIST\nx1.raw\nx2.raw\n");
    files = input_files(dir / "m.nhdr");
    ASSERT_EQ(files.size(), 3u);
    EXPECT_EQ(files[1], dir / "x1.raw");
    // volume-edit p.mhd -o s1.mhd: s1.mhd writes s1.raw, an input's slice of a pattern s%d.raw.
    write_file_atomically(dir / "q.mhd", "ElementDataFile = s%d.raw 1 2 1\n");
    EXPECT_NE(refusal(dir / "s1.mhd", {dir / "q.mhd"}).find("s1.raw"), std::string::npos);
    // A pattern is never handed to printf: other conversions name no file.
    write_file_atomically(dir / "bad.mhd", "ElementDataFile = %s%n 1 3 1\n");
    EXPECT_EQ(input_files(dir / "bad.mhd").size(), 1u);
}

TEST(OutputGuard, WriteAtomicallyRefusesARegisteredInput) {
    const fs::path dir = base("registered");
    write_file_atomically(dir / "S.toml", "name = \"s\"\n");
    protect_input(dir / "S.toml");
    EXPECT_THROW(write_file_atomically(dir / "S.toml", "overwritten"), InputError);
    std::ifstream in(dir / "S.toml");
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "name = \"s\"");
}

// Item 19 / 1: a set of files appears together or not at all.
TEST(FileSet, AFailingMemberLeavesNoneOfTheSet) {
    const fs::path dir = base("set");
    {
        FileSet files;
        files.add(dir / "fit.json", "{}");
        EXPECT_THROW(files.add(dir / "moved.ply",
                               [](const fs::path&) { throw IoError("simulated full disk"); }),
                     IoError);
    }
    EXPECT_FALSE(fs::exists(dir / "fit.json"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 0);
    FileSet files;
    files.add(dir / "fit.json", "{}");
    files.add(dir / "p.ply.json", "{}");
    EXPECT_FALSE(fs::exists(dir / "fit.json"));
    files.commit();
    EXPECT_TRUE(fs::exists(dir / "fit.json"));
    EXPECT_TRUE(fs::exists(dir / "p.ply.json"));
}

}  // namespace
}  // namespace glint
