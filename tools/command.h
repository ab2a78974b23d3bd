// How a subcommand plugs into `glint`: a command_<name>.cpp defines a setup function that adds
// a CLI11 subcommand (with its callback) and registers it with a static CommandRegistrar.
// Its helpers live in namespace glint::cli::<name>_command, so no two commands' helpers meet
// when a unity build (GLINT_UNITY) compiles several commands as one translation unit.
// The callback does the work and throws glint errors; main() maps them to exit codes:
//   0 ok, 1 a check failed (e.g. an [expect] of a scenario), 2 bad input (InputError and
//   command-line errors), 3 device or IO trouble (DeviceError, IoError), 4 internal error.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace glint::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitCheckFailed = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitDeviceOrIo = 3;
inline constexpr int kExitInternal = 4;
inline constexpr int kExitInterrupted = 130;  ///< SIGINT / SIGTERM (128 + SIGINT, as shells do)

/// Flags every subcommand shares (set on the top-level app, read by commands).
struct GlobalFlags {
    bool quiet = false;        ///< no progress or chatter on stderr; results still go to stdout
    bool json = false;         ///< machine-readable JSON on stdout instead of tables
    std::string command_line;  ///< argv joined by spaces (recorded in reports)
};
GlobalFlags& global_flags();

/// `text` as a terminal may show it: control bytes (ESC, BEL, NUL, …; C0, DEL and C1 in
/// UTF-8) written as \xNN, so a file name such as $'\e]0;PWNED\a.ply' retitles no window and a
/// NUL cuts no message (issue 52). Other bytes, UTF-8 included, pass unchanged.
inline std::string terminal_safe(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    const auto escape = [&out](unsigned char c) {
        static const char* hex = "0123456789abcdef";
        out += "\\x";
        out += hex[c >> 4];
        out += hex[c & 15];
    };
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        const auto next = static_cast<unsigned char>(i + 1 < text.size() ? text[i + 1] : '\0');
        if ((c < 0x20 && c != '\t') || c == 0x7f) {
            escape(c);
        } else if (c == 0xc2 && next >= 0x80 && next <= 0x9f) {  // C1 controls (CSI, OSC …)
            escape(c);
            escape(next);
            ++i;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

/// Every warning a report holds, on stderr as "warning: …", one per line. Printed with --quiet
/// and --json too: a warning says the result may not mean what it seems (a capped floor, a
/// scale chosen for the evidence, a poor fit), which is no chatter.
/// `prefix` (a scenario's name) goes before each: "warning: NAME: …".
inline void print_warnings(const std::vector<std::string>& warnings,
                           const std::string& prefix = "") {
    for (const auto& w : warnings)
        std::fprintf(stderr, "warning: %s%s%s\n", terminal_safe(prefix).c_str(),
                     prefix.empty() ? "" : ": ", terminal_safe(w).c_str());
}

/// An output path as --json prints it: absolute and normalised, so a script that started glint
/// elsewhere finds it; "" stays "" (no output).
inline std::string absolute_output(const std::filesystem::path& path) {
    if (path.empty()) return {};
    return std::filesystem::absolute(path).lexically_normal().string();
}

/// Thrown by a command whose run completed but whose checks failed (exit 1).
struct CheckFailed : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Installs the SIGINT / SIGTERM handlers (tools/interrupts.cpp; they are already in place
/// from before the libraries' initialisers) and starts the watchdog: the first signal requests
/// cancellation (mesh/cancel.h: library loops throw Cancelled at their next safe point, the
/// run unwinds, staged outputs are removed and glint exits 130); a step that does not stop
/// within 3 s, or a second signal given a second or more later, ends the process after the
/// watchdog removed the staged outputs. The same signal repeated within a second is one.
void install_interrupt_handlers();
/// The command line printed its own line about the interrupt: the watchdog, should it still
/// end the process, stays silent (one line per run).
void note_interrupt_reported() noexcept;

using CommandSetup = std::function<void(CLI::App& app)>;

/// Registers a subcommand; `order` sorts them in --help.
struct CommandRegistrar {
    CommandRegistrar(int order, CommandSetup setup);
};

/// Registered setups, sorted by order.
void add_registered_commands(CLI::App& app);

}  // namespace glint::cli
