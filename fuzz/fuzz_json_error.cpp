// libFuzzer harness: the --json error path (issue 52). Any bytes as an error message (a file
// name, a scenario's text, another encoding) become one JSON object that parses back, and one
// terminal line without control bytes; nothing throws or aborts (invalid UTF-8 aborted glint).
#include "mesh/json_text.h"
#include "tools/command.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string message(reinterpret_cast<const char*>(data), size);
    // As tools/main.cpp's fail() writes it to stdout with --json.
    const std::string line =
        glint::json_text(nlohmann::json{{"error", message}, {"kind", "error"}, {"exit_code", 2}});
    if (line.find('\n') != std::string::npos) std::abort();  // one line
    const auto back = nlohmann::json::parse(line);           // throws (a finding) if invalid
    if (back.at("exit_code") != 2 || !back.at("error").is_string()) std::abort();
    // As it writes it to stderr: no byte a terminal would take as a control.
    for (const char c : glint::cli::terminal_safe(message)) {
        const auto u = static_cast<unsigned char>(c);
        if ((u < 0x20 && u != '\t') || u == 0x7f) std::abort();
    }
    return 0;
}
