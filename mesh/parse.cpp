#include "mesh/parse.h"

#include "mesh/error.h"

#include <charconv>
#include <cmath>

namespace glint {

std::vector<double> parse_number_list(std::string_view text, const std::string& where,
                                      char separator) {
    std::vector<double> out;
    if (text.empty()) return out;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(separator, start);
        const std::string item(text.substr(
            start, end == std::string_view::npos ? std::string_view::npos : end - start));
        double value = 0.0;
        const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
        if (item.empty() || ec != std::errc() || ptr != item.data() + item.size() ||
            !std::isfinite(value))
            throw InputError(where + ": '" + item + "' is not a number");
        out.push_back(value);
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    return out;
}

}  // namespace glint
