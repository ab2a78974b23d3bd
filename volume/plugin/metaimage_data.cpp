#include "volume/plugin/metaimage_data.h"

#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

namespace glint::detail {

namespace fs = std::filesystem;

MetaImageLayout metaimage_layout(const fs::path& header) {
    MetaImageLayout layout;
    std::ifstream in(header, std::ios::binary);
    std::string line;
    // note: check_metaimage_header has bounded the header to 1024 lines before this runs.
    for (int n = 0; n < 1024 && std::getline(in, line); ++n) {
        const auto start = line.find_first_not_of(" \t");
        const auto eq = line.find('=');
        if (start == std::string::npos || eq == std::string::npos) continue;
        if (line.compare(start, 18, "CompressedDataSize") == 0) {
            std::uint64_t value = 0;
            const std::string text = line.substr(eq + 1);
            const auto digits = text.find_first_not_of(" \t");
            if (digits != std::string::npos &&
                std::from_chars(text.data() + digits, text.data() + text.size(), value).ec ==
                    std::errc())
                layout.compressed_bytes = value;
        }
        if (line.compare(start, 15, "ElementDataFile") == 0) {
            const auto at = in.tellg();
            if (at >= 0) layout.data_offset = static_cast<std::uint64_t>(at);
            break;
        }
    }
    return layout;
}

namespace {

std::string bytes(std::uint64_t n) { return std::to_string(n) + " bytes"; }

std::string inflate_problem(std::ifstream& in, std::uint64_t stored, std::uint64_t expected) {
    z_stream z{};
    if (inflateInit2(&z, 15 + 32) != Z_OK) return "zlib could not start";  // zlib or gzip
    std::vector<unsigned char> input(1 << 16), output(1 << 16);
    std::uint64_t left = stored, produced = 0;
    int status = Z_OK;
    while (status != Z_STREAM_END) {
        if (z.avail_in == 0) {
            if (left == 0) break;
            in.read(reinterpret_cast<char*>(input.data()),
                    static_cast<std::streamsize>(std::min<std::uint64_t>(left, input.size())));
            const auto got = static_cast<std::uint64_t>(in.gcount());
            if (got == 0) break;
            left -= got;
            z.next_in = input.data();
            z.avail_in = static_cast<uInt>(got);
        }
        z.next_out = output.data();
        z.avail_out = static_cast<uInt>(output.size());
        status = inflate(&z, Z_NO_FLUSH);
        produced += output.size() - z.avail_out;
        if (status != Z_OK && status != Z_STREAM_END) break;
        if (produced > expected) break;
    }
    const std::string zlib_said = z.msg != nullptr ? std::string(" (zlib: ") + z.msg + ")" : "";
    inflateEnd(&z);
    if (status != Z_OK && status != Z_STREAM_END)
        return "its compressed voxels do not inflate" + zlib_said + " after " + bytes(produced) +
               ", the header needs " + bytes(expected);
    if (produced > expected)
        return "its compressed voxels inflate to more than the " + bytes(expected) +
               " the header needs";
    if (status != Z_STREAM_END || produced != expected)
        return "its compressed voxels end after " + bytes(produced) + " of the " + bytes(expected) +
               " the header needs";
    return "";
}

}  // namespace

std::string metaimage_voxel_problem(const fs::path& file, const StoredVoxels& stored) {
    std::error_code ec;
    const std::uint64_t size = fs::file_size(file, ec);
    if (ec) return "cannot read the size of \"" + file.string() + "\": " + ec.message();
    const std::uint64_t available = size >= stored.offset ? size - stored.offset : 0;
    if (!stored.compressed) {
        if (available == stored.expected) return "";
        return "holds " + bytes(available) + " of voxels" +
               (stored.offset > 0 ? " after its header" : "") + ", the header needs " +
               bytes(stored.expected);
    }
    if (stored.compressed_bytes && *stored.compressed_bytes > available)
        return "CompressedDataSize is " + std::to_string(*stored.compressed_bytes) +
               ", the file holds " + bytes(available) +
               (stored.offset > 0 ? " after its header" : "");
    std::ifstream in(file, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(stored.offset));
    if (!in) return "cannot read \"" + file.string() + "\"";
    return inflate_problem(in, stored.compressed_bytes.value_or(available), stored.expected);
}

}  // namespace glint::detail
