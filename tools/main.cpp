// glint: damage detection on 3D surfaces by light-reflection analysis.
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/io.h"
#include "tools/command.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <exception>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace glint::cli {

GlobalFlags& global_flags() {
    static GlobalFlags flags;
    return flags;
}

namespace {
extern "C" void on_signal(int signal) {
    glint::request_cancel(signal);
    std::signal(signal, SIG_DFL);  // a second one ends the process at once
}

std::vector<std::pair<int, CommandSetup>>& registry() {
    static std::vector<std::pair<int, CommandSetup>> commands;
    return commands;
}
}  // namespace

CommandRegistrar::CommandRegistrar(int order, CommandSetup setup) {
    registry().emplace_back(order, std::move(setup));
}

void install_interrupt_handlers() {
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
}

void add_registered_commands(CLI::App& app) {
    auto& commands = registry();
    std::stable_sort(commands.begin(), commands.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& [order, setup] : commands) setup(app);
}

}  // namespace glint::cli

int main(int argc, char** argv) {
    using namespace glint::cli;
    CLI::App app{"glint: finds damage on 3D surfaces by light-reflection analysis"};
    app.set_version_flag("--version", "glint 0.1.0");
    app.require_subcommand(1);
    app.fallthrough();
    auto& flags = global_flags();
    app.add_flag("-q,--quiet", flags.quiet, "No progress bars or chatter on stderr");
    app.add_flag("--json", flags.json, "Machine-readable JSON on stdout");
    // note: a global option (fallthrough lets it follow any subcommand); it sets the budget
    // of every mesh load, scenarios' included, before any command runs.
    app.add_option_function<std::uint64_t>(
           "--max-triangles", [](const std::uint64_t& n) { glint::set_default_max_triangles(n); },
           "Refuse meshes with more triangles than this (default " +
               std::to_string(glint::kDefaultMaxTriangles) + ")")
        ->check(CLI::PositiveNumber);
    add_registered_commands(app);
    install_interrupt_handlers();
    for (int i = 0; i < argc; ++i) {
        if (i > 0) global_flags().command_line += ' ';
        global_flags().command_line += argv[i];
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? kExitOk : kExitBadInput;
    } catch (const glint::Cancelled& e) {
        std::cerr << "glint: interrupted: " << e.what() << '\n';
        return kExitInterrupted;
    } catch (const CheckFailed& e) {
        std::cerr << "glint: check failed: " << e.what() << '\n';
        return kExitCheckFailed;
    } catch (const glint::InputError& e) {
        std::cerr << "glint: error: " << e.what() << '\n';
        return kExitBadInput;
    } catch (const glint::IoError& e) {
        std::cerr << "glint: error: " << e.what() << '\n';
        return kExitDeviceOrIo;
    } catch (const glint::DeviceError& e) {
        std::cerr << "glint: device error: " << e.what() << '\n';
        return kExitDeviceOrIo;
    } catch (const std::exception& e) {
        std::cerr << "glint: internal error: " << e.what() << '\n';
        return kExitInternal;
    }
    return kExitOk;
}
