// report.html's asymmetry section (glint asymmetry, glint.asymmetry()): from report.json's
// "asymmetry" object (report/asymmetry_json.h), as markup the page shows without its scripts:
// the symmetry plane (normal, point, angles to the file's axes, residual with its unit,
// overlap, verdict), the symmetry floor, the one-scan caveat, and the findings side by side,
// one row each (side, kind, depth, area, volume with their units, the sentence).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace glint {

/// The section's markup; "" when the report has no "asymmetry" object (a sweep's report).
/// Every text is escaped (report_html.h escape_markup).
[[nodiscard]] std::string asymmetry_section_html(const nlohmann::json& report);

}  // namespace glint
