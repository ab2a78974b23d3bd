// Small text parsers shared by the command line, scenario and spec readers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// Numbers separated by `separator` ("1,2.5,-3"). `where` names the text in the error:
/// InputError "<where>: 'x' is not a number". An empty text gives no numbers.
[[nodiscard]] std::vector<double> parse_number_list(std::string_view text, const std::string& where,
                                                    char separator = ',');

}  // namespace glint
