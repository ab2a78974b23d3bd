// read_npy_mask (scenario/scenario.h): the tooth-wear ground-truth masks, NumPy .npy files.
#include "mesh/error.h"
#include "mesh/small_file.h"
#include "scenario/scenario.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <sstream>

namespace glint {

namespace fs = std::filesystem;

std::vector<std::uint8_t> read_npy_mask(const fs::path& path) {
    const std::string bytes = read_small_file(path, "mask", std::size_t{1} << 30);
    std::istringstream in(bytes);
    char magic[8] = {};
    in.read(magic, 8);
    if (!in || std::memcmp(magic, "\x93NUMPY", 6) != 0)
        throw InputError("mask \"" + path.string() + "\": not a NumPy .npy file (bad magic)");
    const int major = static_cast<unsigned char>(magic[6]);
    const std::uintmax_t file_size = bytes.size();
    std::uint32_t header_len = 0;
    unsigned char b[4] = {};
    in.read(reinterpret_cast<char*>(b), major == 1 ? 2 : 4);
    for (int i = (major == 1 ? 1 : 3); i >= 0; --i) header_len = (header_len << 8) | b[i];
    // note: a header longer than the file is a lie; refuse it before allocating for it.
    if (!in || header_len > file_size)
        throw InputError("mask \"" + path.string() + "\": header length " +
                         std::to_string(header_len) + " exceeds the file's " +
                         std::to_string(file_size) + " bytes");
    std::string header(header_len, '\0');
    in.read(header.data(), header_len);
    if (!in) throw InputError("mask \"" + path.string() + "\": truncated header");
    if (header.find("'|b1'") == std::string::npos && header.find("'|u1'") == std::string::npos)
        throw InputError("mask \"" + path.string() + "\": dtype is not bool or uint8 (header " +
                         header + ")");
    if (header.find("'fortran_order': False") == std::string::npos)
        throw InputError("mask \"" + path.string() + "\": expected C order");
    const auto open = header.find("'shape': (");
    if (open == std::string::npos)
        throw InputError("mask \"" + path.string() + "\": no shape in header");
    std::size_t count = 0;
    const char* first = header.data() + open + 10;
    const auto parsed = std::from_chars(first, header.data() + header.size(), count);
    const std::uintmax_t data_bytes =
        file_size - std::min<std::uintmax_t>(file_size, static_cast<std::uintmax_t>(in.tellg()));
    if (parsed.ec != std::errc() || count > data_bytes)
        throw InputError("mask \"" + path.string() + "\": header says " +
                         std::string(first, parsed.ptr) + " values, the file holds " +
                         std::to_string(data_bytes));
    std::vector<std::uint8_t> mask(count);
    in.read(reinterpret_cast<char*>(mask.data()), static_cast<std::streamsize>(count));
    if (static_cast<std::size_t>(in.gcount()) != count)
        throw InputError("mask \"" + path.string() + "\": header says " + std::to_string(count) +
                         " values, file has " + std::to_string(in.gcount()));
    for (auto& m : mask) m = m ? 1 : 0;
    return mask;
}

}  // namespace glint
