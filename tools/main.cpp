// glint: damage detection on 3D surfaces by light-reflection analysis.
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/input_path.h"
#include "mesh/io.h"
#include "mesh/json_text.h"
#include "mesh/memory_limits.h"
#include "mesh/plugin_library.h"
#include "mesh/version.h"
#include "tools/command.h"
#include "tools/progress.h"
#include "tools/slicer_module.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <csignal>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace glint::cli {

GlobalFlags& global_flags() {
    static GlobalFlags flags;
    return flags;
}

namespace {
std::vector<std::pair<int, CommandSetup>>& registry() {
    static std::vector<std::pair<int, CommandSetup>> commands;
    return commands;
}
}  // namespace

CommandRegistrar::CommandRegistrar(int order, CommandSetup setup) {
    registry().emplace_back(order, std::move(setup));
}

void add_registered_commands(CLI::App& app) {
    auto& commands = registry();
    std::stable_sort(commands.begin(), commands.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& [order, setup] : commands) setup(app);
}

}  // namespace glint::cli

namespace {

using namespace glint::cli;

// One line on stderr, "glint: <kind>: <message>"; with --json also {"error": …} on stdout, so
// a script reading stdout learns why there is no result.
int fail(int code, const std::string& kind, const std::string& message) {
    std::cerr << "glint: " << kind << ": " << terminal_safe(message) << '\n';
    if (global_flags().json)
        std::cout << glint::json_text(
                         nlohmann::json{{"error", message}, {"kind", kind}, {"exit_code", code}})
                  << '\n';
    return code;
}

std::string command_list(CLI::App& app) {
    std::string names;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        names += (names.empty() ? "" : ", ") + sub->get_name();
    return names;
}

// Looks at the words before CLI11 does: --json (so even a parse error is reported as JSON)
// and the command word, which must name a command. Returns a message when it does not.
std::string check_command_word(CLI::App& app, int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word == "--json") {
            global_flags().json = true;
            continue;
        }
        if (word == "--max-triangles") {  // the one global option with a separate value
            ++i;
            continue;
        }
        if (word.starts_with("-")) continue;  // global flags, --help, --version: CLI11's
        for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
            if (sub->check_name(word)) return "";
        return "unknown command '" + word + "'; commands: " + command_list(app);
    }
    return "";
}

// CLI11's own errors ("EXA is required") in glint's one-line form, naming the command.
int parse_failure(CLI::App& app, const CLI::ParseError& e) {
    if (e.get_exit_code() == 0)
        return app.exit(e) == 0 ? kExitOk : kExitBadInput;  // --help, --version
    const auto parsed = app.get_subcommands();
    if (parsed.empty()) {
        if (dynamic_cast<const CLI::RequiredError*>(&e))
            return fail(
                kExitBadInput, "error",
                "a command is required; commands: " + command_list(app) + " (glint --help)");
        return fail(kExitBadInput, "error", std::string(e.what()) + " (glint --help)");
    }
    const std::string name = parsed.front()->get_name();
    return fail(kExitBadInput, "error", name + ": " + e.what() + " (glint " + name + " --help)");
}

// note: triangle indices are 32-bit: no mesh holds more than 2^32 - 1 triangles.
constexpr std::uint64_t kMaxTrianglesLimit = 4294967295u;

// --max-triangles N: an integer from 1 to 2^32 - 1 (0 printed a 309-digit range, 2^64 passed).
std::uint64_t parse_max_triangles(const std::string& text) {
    std::uint64_t n = 0;
    const char* end = text.data() + text.size();
    const auto [at, ec] = std::from_chars(text.data(), end, n);
    if (ec != std::errc() || at != end || n < 1 || n > kMaxTrianglesLimit)
        throw glint::InputError("--max-triangles = " + text + ": expected an integer from 1 to " +
                                std::to_string(kMaxTrianglesLimit));
    return n;
}

// Runs the command; every glint error becomes its one line and exit code.
int guarded(CLI::App& app, const std::function<void()>& body) {
    try {
        body();
    } catch (const CLI::ParseError& e) {
        return parse_failure(app, e);
    } catch (const glint::Cancelled& e) {
        note_interrupt_reported();
        return fail(kExitInterrupted, "interrupted", e.what());
    } catch (const CheckFailed& e) {
        // The command printed its result (JSON too) before its checks failed: stderr only.
        std::cerr << "glint: check failed: " << e.what() << '\n';
        return kExitCheckFailed;
    } catch (const glint::InputError& e) {
        return fail(kExitBadInput, "error", e.what());
    } catch (const glint::IoError& e) {
        return fail(kExitDeviceOrIo, "error", e.what());
    } catch (const glint::DeviceError& e) {
        return fail(kExitDeviceOrIo, "device error", e.what());
    } catch (const std::bad_alloc&) {
        const std::string& line = global_flags().command_line;
        const std::string stage = last_stage();
        return fail(kExitDeviceOrIo, "out of memory",
                    "`" + line.substr(0, 200) + "` needed more memory than it could get" +
                        (stage.empty() ? "" : " in its stage \"" + stage + "\"") + " (" +
                        glint::memory_limits_text() + ")");
    } catch (const std::filesystem::filesystem_error& e) {
        // A file-system call no reader checked first: the machine's problem, not glint's.
        const glint::PathCheck why = glint::check_path(e.path1());
        return fail(kExitDeviceOrIo, "error",
                    "\"" + e.path1().string() + "\": " +
                        (why.reach == glint::PathReach::Denied ? why.reason : e.code().message()));
    } catch (const std::exception& e) {
        return fail(kExitInternal, "internal error", e.what());
    }
    // A signal that came after the last point that polls (the outputs' commit): the results
    // are complete and kept, but the request to stop is not swallowed.
    if (glint::cancel_requested()) {
        note_interrupt_reported();
        const int s = glint::cancel_signal();
        return fail(kExitInterrupted, "interrupted",
                    std::string(s == SIGINT    ? "SIGINT"
                                : s == SIGTERM ? "SIGTERM"
                                               : "a signal") +
                        " received after the command completed; its results are complete and "
                        "kept");
    }
    return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace glint::cli;
    CLI::App app{"glint: finds damage on 3D surfaces by light-reflection analysis"};
    app.set_version_flag("--version", std::string("glint ") + glint::kVersion);
    app.require_subcommand(1);
    app.fallthrough();
    auto& flags = global_flags();
    app.add_flag("-q,--quiet", flags.quiet,
                 "No progress or chatter on stderr (results and warnings are still printed)");
    app.add_flag("--json", flags.json,
                 "Machine-readable JSON on stdout (errors too: {\"error\": …})");
    // note: a global option (fallthrough lets it follow any subcommand); it sets the budget
    // of every mesh load, scenarios' included, before any command runs.
    app.add_option_function<std::string>(
        "--max-triangles",
        [](const std::string& text) {
            glint::set_default_max_triangles(parse_max_triangles(text));
        },
        "Refuse meshes with more triangles than this (default " +
            std::to_string(glint::kDefaultMaxTriangles) + ", at most " +
            std::to_string(kMaxTrianglesLimit) + ")");
    add_registered_commands(app);
    install_interrupt_handlers();
    for (int i = 0; i < argc; ++i) {
        if (i > 0) global_flags().command_line += ' ';
        global_flags().command_line += argv[i];
    }
    // A call shaped like 3D Slicer's (glint --xml, then flags and index arguments: see
    // tools/slicer_module.h) runs the sweep as a Slicer module.
    int code = kExitOk;
    if (is_slicer_call(argc, argv)) {
        code = guarded(app, [&] { run_slicer_module(argc, argv); });
    } else if (const std::string unknown = check_command_word(app, argc, argv); !unknown.empty()) {
        code = fail(kExitBadInput, "error", unknown);
    } else {
        code = guarded(app, [&] {
            glint::throw_if_cancelled();  // a signal during start-up: no work begins
            app.parse(argc, argv);
        });
    }
    // A plugin still loading (a run stopped or refused in its first half second) ends its
    // dlopen before exit begins: exit runs the destructors its libraries register at once,
    // and the rest of their start-up then used a logger already destroyed (a stray
    // "log4cplus:ERROR" line after the run's one line).
    glint::detail::finish_background_loads();
    return code;
}
