// The analysis sections of a scenario file ([registration], [sweep], [threshold],
// [decision]) read into AnalysisOptions, and their check with file and line. Internal to
// scenario/scenario.cpp.
#pragma once

#include "analysis/analysis.h"
#include "report/export_options.h"
#include "scenario/detail/toml_reader.h"

#include <filesystem>
#include <string>

namespace glint::detail {

/// Reads the sections present (unknown keys and wrong types fail with file, line, key);
/// relative paths are resolved against `scenario_dir`.
void read_analysis_sections(TableReader& top, const std::filesystem::path& scenario_dir,
                            AnalysisOptions& options);

/// The [exports] section, when present: what a run of the scenario writes (pictures, views,
/// atlas files, which way is up), the keys of export_option_table(). Fails as above.
void read_export_section(TableReader& top, const std::filesystem::path& scenario_dir,
                         ExportOptions& exports);

/// options.validate(), with an OptionError turned into "scenario \"F\" line L: [section] key …".
void validate_analysis_sections(const toml::table& root, const std::string& file,
                                const AnalysisOptions& options);

}  // namespace glint::detail
