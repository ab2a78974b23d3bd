// MetaImage voxels against the header (issue 23, item 18): MetaIO read LOCAL data that came up
// short, or compressed data that did not inflate, with chatter on stderr and no error (the
// missing voxels became zeros, exit 0). Each is now one InputError naming the file and sizes;
// well-formed raw and compressed files, LOCAL or detached, read as before.
#include "mesh/error.h"
#include "tests/mesh/test_files.h"
#include "volume/volume.h"

#include <gtest/gtest.h>

#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) { return test::fresh_dir("metaimage_data", name); }

// 4 x 4 x 4 shorts, value = index.
std::string voxel_bytes() {
    std::string bytes;
    for (std::int16_t i = 0; i < 64; ++i) bytes.append(reinterpret_cast<const char*>(&i), sizeof i);
    return bytes;
}

std::string deflated(const std::string& raw) {
    uLongf size = compressBound(static_cast<uLong>(raw.size()));
    std::string out(size, '\0');
    EXPECT_EQ(compress(reinterpret_cast<Bytef*>(out.data()), &size,
                       reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size())),
              Z_OK);
    out.resize(size);
    return out;
}

std::string header(const std::string& data_file, const std::string& compression = "") {
    return "ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_SHORT\n" +
           compression + "ElementDataFile = " + data_file + "\n";
}

fs::path write(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

std::string message_of(const fs::path& path) {
    try {
        (void)read_volume(path);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << path << " was read";
    return "";
}

void expect_index_values(const fs::path& path) {
    SCOPED_TRACE(path.filename().string());
    const Volume v = read_volume(path);
    ASSERT_EQ(v.voxels.size(), 64u);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < 64; ++i) wrong += v.voxels[i] != static_cast<float>(i) ? 1 : 0;
    EXPECT_EQ(wrong, 0u) << "voxels not as written; the first is " << v.voxels[0];
}

TEST(MetaImageVoxels, WellFormedRawAndCompressedFilesReadAsBefore) {
    const fs::path dir = fresh_dir("good");
    const std::string z = deflated(voxel_bytes());
    expect_index_values(write(dir / "raw.mha", header("LOCAL") + voxel_bytes()));
    expect_index_values(
        write(dir / "z.mha", header("LOCAL", "CompressedData = True\nCompressedDataSize = " +
                                                 std::to_string(z.size()) + "\n") +
                                 z));
    write(dir / "d.zraw", z);
    expect_index_values(write(dir / "d.mhd", header("d.zraw", "CompressedData = True\n")));
}

TEST(MetaImageVoxels, LocalDataCutShortIsRefusedWithItsSizes) {
    const fs::path dir = fresh_dir("short");
    const std::string m =
        message_of(write(dir / "a.mha", header("LOCAL") + voxel_bytes().substr(0, 50)));
    EXPECT_NE(m.find("\"" + (dir / "a.mha").string() + "\""), std::string::npos) << m;
    EXPECT_NE(m.find("holds 50 bytes of voxels after its header, the header needs 128 bytes"),
              std::string::npos)
        << m;
    // A header long enough for the voxels, whose last line is ElementDataFile = LOCAL.
    const std::string none = "Comment = " + std::string(150, 'c') + "\n" + header("LOCAL");
    EXPECT_NE(message_of(write(dir / "none.mha", none.substr(0, none.size() - 1)))
                  .find("no voxels follow its header"),
              std::string::npos);
}

// MetaIO reads LOCAL compressed voxels only as far as CompressedDataSize says: without it the
// volume came back as uninitialised memory.
TEST(MetaImageVoxels, LocalCompressedDataWithoutItsSizeIsRefused) {
    const fs::path dir = fresh_dir("unsized");
    const std::string m = message_of(
        write(dir / "z.mha", header("LOCAL", "CompressedData = True\n") + deflated(voxel_bytes())));
    EXPECT_NE(m.find("CompressedData = True without CompressedDataSize"), std::string::npos) << m;
}

TEST(MetaImageVoxels, CompressedDataThatDoesNotInflateIsRefused) {
    const fs::path dir = fresh_dir("garbage");
    const std::string m = message_of(
        write(dir / "b.mha", header("LOCAL", "CompressedData = True\nCompressedDataSize = 40\n") +
                                 std::string(40, '\x55')));
    EXPECT_NE(m.find("its compressed voxels do not inflate (zlib: "), std::string::npos) << m;
}

TEST(MetaImageVoxels, CompressedDataCutOrShortIsRefused) {
    const fs::path dir = fresh_dir("cut");
    const std::string z = deflated(voxel_bytes());
    const std::string stated =
        "CompressedData = True\nCompressedDataSize = " + std::to_string(z.size()) + "\n";
    EXPECT_NE(message_of(write(dir / "cut.mha", header("LOCAL", stated) + z.substr(0, 10)))
                  .find("CompressedDataSize is " + std::to_string(z.size()) +
                        ", the file holds 10 bytes after its header"),
              std::string::npos);
    const std::string fewer = deflated(voxel_bytes().substr(0, 100));
    const std::string few_size =
        "CompressedData = True\nCompressedDataSize = " + std::to_string(fewer.size()) + "\n";
    EXPECT_NE(message_of(write(dir / "few.mha", header("LOCAL", few_size) + fewer))
                  .find("its compressed voxels end after 100 bytes of the 128 bytes the header "
                        "needs"),
              std::string::npos);
    write(dir / "d.zraw", z.substr(0, z.size() / 2));
    EXPECT_NE(message_of(write(dir / "d.mhd", header("d.zraw", "CompressedData = True\n")))
                  .find("data file \"" + (dir / "d.zraw").string() + "\": its compressed voxels"),
              std::string::npos);
}

// MetaIO printed four lines ("DimSize defined prior to defining NDims", "MET_Read Failed", …)
// and ITK's error said "File cannot be read … Reason: Invalid argument".
TEST(MetaImageVoxels, MetaIOsReasonIsTheMessageAndNothingReachesStderr) {
    const fs::path dir = fresh_dir("order");
    const fs::path path = write(dir / "e.mha",
                                "ObjectType = Image\nDimSize = 4 4 4\nNDims = 3\n"
                                "ElementType = MET_SHORT\nElementDataFile = "
                                "LOCAL\n" +
                                    voxel_bytes());
    testing::internal::CaptureStderr();
    const std::string m = message_of(path);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_NE(m.find("MetaImage header: DimSize defined prior to defining NDims; expected"),
              std::string::npos)
        << m;
}

}  // namespace
}  // namespace glint
