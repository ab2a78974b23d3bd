#include "tools/option_flags.h"

#include "mesh/error.h"

#include <iostream>
#include <string>

namespace glint::cli {

namespace {

// "(default 30; deg)": what --help shows after the registry's help line.
std::string default_note(const OptionInfo& info, const OptionValue& current) {
    std::string note;
    if (info.kind == OptionKind::Choice || info.kind == OptionKind::Flag)
        note = describe_expected(info);
    const std::string shown = option_text(info, current);
    if (!shown.empty() && info.kind != OptionKind::Flag)
        note += (note.empty() ? "default " : "; default ") + shown;
    else if (info.kind == OptionKind::Flag)
        note += std::string("; default ") + (shown == "true" ? "on" : "off");
    if (!info.unit.empty()) note += (note.empty() ? "" : "; ") + std::string(info.unit);
    return note.empty() ? "" : " (" + note + ")";
}

}  // namespace

void add_option_flag(CLI::App& cmd, const OptionInfo& info, const OptionValue& current,
                     std::function<void(OptionValue)> set) {
    const std::string flag = info.flag();
    const std::string help = std::string(info.help) + default_note(info, current);
    if (info.kind == OptionKind::Flag) {
        // --name sets it, --no-name clears it; both at once is a mistake CLI11 refuses.
        auto* on = cmd.add_flag_callback(
            flag, [set, info] { set(check_value(info, true)); }, help);
        auto* off = cmd.add_flag_callback(
            "--no-" + flag.substr(2), [set, info] { set(check_value(info, false)); },
            "Turns " + flag + " off");
        on->excludes(off);
        return;
    }
    cmd.add_option_function<std::string>(
           flag,
           [set, info, flag](const std::string& text) {
               try {
                   set(parse_option_text(info, text));
               } catch (const OptionError& e) {
                   throw InputError(e.named(flag));  // the command line names its flag
               }
           },
           help)
        ->allow_extra_args(false);
}

void add_analysis_flags(CLI::App& cmd, AnalysisOptions& options, unsigned groups) {
    add_option_flags(cmd, options, analysis_option_table(), groups);
}

void add_fit_mode_flags(CLI::App& cmd, FitOptions& fit) {
    auto* file = cmd.add_option_function<std::string>(
        "--fit",
        [&fit](const std::string& v) {
            fit.mode = FitMode::File;
            fit.fit_file = v;
        },
        "fit.json from glint register (examined → reference)");
    auto* reg = cmd.add_flag_callback(
        "--register", [&fit] { fit.mode = FitMode::Register; },
        "Fit the examined mesh now (robust ICP)");
    file->excludes(reg);
}

void add_print_options_flag(CLI::App& cmd, bool& print) {
    cmd.add_flag("--print-options", print,
                 "Print the resolved analysis options as JSON and stop (loads nothing)");
}

void print_options(const AnalysisOptions& options, const ExportOptions& exports) {
    std::cout << to_json(options, exports) << '\n';
}

}  // namespace glint::cli
