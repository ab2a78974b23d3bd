// JSON text that never throws on what a user named: a file name, a mesh's comment or an error
// message may hold bytes that are not UTF-8 (another encoding, a fuzzed name), and
// nlohmann::json::dump() throws type_error 316 on them (a --json error line aborted the
// program; a whole analysis ran, then wrote nothing: issue 52).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace glint {

/// `j` as JSON text (`indent` as nlohmann's dump; -1: one line). Bytes that are not UTF-8 are
/// written as U+FFFD, so the text is always valid JSON and the call never throws.
inline std::string json_text(const nlohmann::json& j, int indent = -1) {
    return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace glint
