// glint options: every option of an analysis as the option registry declares it
// (analysis/option_registry.h, report/export_options.h): its command-line flag, scenario key,
// Python keyword and Slicer name, type, default, unit, accepted values and meaning.
#include "analysis/analysis.h"
#include "analysis/option_registry.h"
#include "mesh/json_text.h"
#include "report/export_options.h"
#include "tools/command.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

namespace glint::cli::options_command {
namespace {

const char* kind_name(OptionKind k) {
    switch (k) {
        case OptionKind::Flag: return "flag";
        case OptionKind::Integer: return "integer";
        case OptionKind::Number: return "number";
        case OptionKind::OptionalNumber: return "optional number";
        case OptionKind::Numbers: return "numbers";
        case OptionKind::Choice: return "choice";
        case OptionKind::Text: return "text";
        case OptionKind::Region: return "region";
        case OptionKind::Path: return "path";
    }
    return "?";
}

const char* group_name(OptionGroup g) {
    switch (g) {
        case kUnitGroup: return "units";
        case kFitGroup: return "fit";
        case kSweepGroup: return "sweep";
        case kDecisionGroup: return "decision";
        case kExportGroup: return "exports";
    }
    return "?";
}

nlohmann::json number_or_null(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

template <class Options>
void describe_table(const std::vector<OptionField<Options>>& table, nlohmann::json& out) {
    const Options defaults{};
    for (const auto& f : table) {
        const OptionInfo& i = f.info;
        const std::string def = option_text(i, f.get(defaults));
        if (global_flags().json) {
            out.push_back({{"name", std::string(i.name)},
                           {"flag", i.flag()},
                           {"toml", i.path()},
                           {"python", std::string(i.name)},
                           {"slicer", i.group == kExportGroup ? "" : std::string(i.slicer)},
                           {"group", group_name(i.group)},
                           {"kind", kind_name(i.kind)},
                           {"default", def},
                           {"unit", std::string(i.unit)},
                           {"min", number_or_null(i.min)},
                           {"max", number_or_null(i.max)},
                           {"min_exclusive", i.min_exclusive},
                           {"max_exclusive", i.max_exclusive},
                           {"may_be_unset", i.may_be_unset},
                           {"choices", i.choices},
                           {"expected", describe_expected(i)},
                           {"help", std::string(i.help)}});
            continue;
        }
        std::printf("%-30s %-10s default %s%s\n    %s; %s\n    scenario %s, Python %s%s%s\n",
                    i.flag().c_str(), group_name(i.group), def.empty() ? "(unset)" : def.c_str(),
                    i.unit.empty() ? "" : (" " + std::string(i.unit)).c_str(),
                    std::string(i.help).c_str(), describe_expected(i).c_str(), i.path().c_str(),
                    std::string(i.name).c_str(), i.group == kExportGroup ? "" : ", Slicer ",
                    i.group == kExportGroup ? "" : std::string(i.slicer).c_str());
    }
}

void run() {
    nlohmann::json out = nlohmann::json::array();
    describe_table(analysis_option_table(), out);
    describe_table(export_option_table(), out);
    if (global_flags().json) std::cout << json_text(out, 2) << '\n';
}

void setup(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "options",
        "Every analysis option: its flag, scenario key, Python keyword, Slicer name, default and "
        "meaning (--json for scripts)");
    cmd->callback([] { run(); });
}

const CommandRegistrar registrar(95, setup);

}  // namespace
}  // namespace glint::cli::options_command
