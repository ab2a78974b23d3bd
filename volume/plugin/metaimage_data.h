// A MetaImage's voxels checked against its header before MetaIO reads them (issue 23, item 18).
// MetaIO reads LOCAL data that comes up short, or compressed data that does not inflate, with
// lines of chatter on stderr ("M_ReadElementsData: data not read completely", "Uncompress
// failed") and no error: the volume came back with missing voxels as zeros, exit 0.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace glint::detail {

/// What glint needs from a MetaImage header that MetaIO does not tell: where LOCAL voxels
/// begin (just after the ElementDataFile line; nullopt when that line ends the file or is
/// missing) and CompressedDataSize (nullopt when not given).
struct MetaImageLayout {
    std::optional<std::uint64_t> data_offset;
    std::optional<std::uint64_t> compressed_bytes;
};
[[nodiscard]] MetaImageLayout metaimage_layout(const std::filesystem::path& header);

/// How a MetaImage's voxels are stored in `file`, from `offset` on.
struct StoredVoxels {
    std::uint64_t offset = 0;
    bool compressed = false;
    std::optional<std::uint64_t> compressed_bytes;  ///< CompressedDataSize, when given
    std::uint64_t expected = 0;                     ///< bytes of voxels the header needs
};

/// "" when the stored bytes give exactly `expected` bytes of voxels (raw, or inflated with
/// zlib: zlib or gzip streams); otherwise what is wrong, in words ("holds 50 bytes of voxels
/// after its header, the header needs 128"). Reads the file once, inflating in small pieces.
[[nodiscard]] std::string metaimage_voxel_problem(const std::filesystem::path& file,
                                                  const StoredVoxels& stored);

}  // namespace glint::detail
