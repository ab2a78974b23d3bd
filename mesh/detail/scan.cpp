#include "mesh/detail/scan.h"

#include "mesh/error.h"

#include <algorithm>

namespace glint::detail {

bool next_line(std::span<const char> data, std::size_t& pos, std::string_view& line) {
    if (pos >= data.size()) return false;
    const char* begin = data.data() + pos;
    const void* nl = std::memchr(begin, '\n', data.size() - pos);
    const std::size_t len =
        nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - begin) : data.size() - pos;
    line = std::string_view(begin, len);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos += len + (nl ? 1 : 0);
    return true;
}

std::vector<std::string_view> split_words(std::string_view line) {
    auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i])) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

bool iequals(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return (x | 0x20) == (y | 0x20);
           });
}

std::string printable(std::string_view s, std::size_t max) {
    std::string t(s.substr(0, max));
    for (char& c : t)
        if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return t;
}

void check_count_fits(std::uint64_t count, std::uint64_t min_bytes, std::uint64_t bytes_left,
                      const std::string& source, const std::string& what) {
    const std::uint64_t per_item = std::max<std::uint64_t>(min_bytes, 1);
    if (count <= bytes_left / per_item) return;
    throw InputError("mesh \"" + source + "\": " + what + " declares " + std::to_string(count) +
                     " items of at least " + std::to_string(per_item) + " byte(s) each, but only " +
                     std::to_string(bytes_left) +
                     " bytes follow: the file is truncated or the count is wrong");
}

void check_triangle_budget(std::uint64_t triangles, std::uint64_t max_triangles,
                           const std::string& source, const std::string& what) {
    if (triangles <= max_triangles) return;
    throw InputError("mesh \"" + source + "\": " + what + " " + std::to_string(triangles) +
                     " triangles, more than the limit " + std::to_string(max_triangles) +
                     " (--max-triangles)");
}

}  // namespace glint::detail
