// Command-line flags generated from the option registry (analysis/option_registry.h): one flag
// per option, --<name with dashes>, with the registry's help, default and unit. A flag's text
// is read and checked while the command line is parsed, so a bad value fails before anything is
// loaded; flags that default to true also take --no-<name>.
#pragma once

#include "analysis/analysis.h"
#include "analysis/option_registry.h"
#include "report/export_options.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace glint::cli {

/// Adds one flag for `info`; `set` receives the checked value (the flag given), `current` is
/// the default shown in --help.
void add_option_flag(CLI::App& command, const OptionInfo& info, const OptionValue& current,
                     std::function<void(OptionValue)> set);

/// Adds the flags of every option of `table` in `groups`, bound to `options`.
template <class Options>
void add_option_flags(CLI::App& command, Options& options,
                      const std::vector<OptionField<Options>>& table, unsigned groups) {
    for (const auto& field : table)
        if ((field.info.group & groups) != 0)
            add_option_flag(command, field.info, field.get(options),
                            [&options, &field](OptionValue v) { field.set(options, v); });
}

/// The analysis flags of `groups` (kUnitGroup, kFitGroup, …) bound to `options`.
void add_analysis_flags(CLI::App& command, AnalysisOptions& options, unsigned groups);

/// How the examined mesh is fitted: --fit FILE | --register (not options of the registry: the
/// command line's default is to take the meshes as aligned).
void add_fit_mode_flags(CLI::App& command, FitOptions& fit);

/// --print-options: print the resolved options as JSON and stop, loading nothing.
void add_print_options_flag(CLI::App& command, bool& print);

/// Prints to_json(options, exports) on stdout.
void print_options(const AnalysisOptions& options, const ExportOptions& exports = {});

}  // namespace glint::cli
