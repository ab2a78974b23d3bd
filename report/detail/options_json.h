// The options as a JSON object for report.json (report/report.cpp), without going through text
// (report/options_json.cpp; to_json in report/export_options.h is its text). Internal to report/.
#pragma once

#include "analysis/analysis.h"
#include "report/export_options.h"

#include <nlohmann/json.hpp>

namespace glint::detail {

[[nodiscard]] nlohmann::json options_object(const AnalysisOptions& options,
                                            const ExportOptions& exports);

}  // namespace glint::detail
