// The footer of atlas.png (private to report/): what a picture cited alone must carry — both
// input files, the date of the run, the fit that put the examined surface on the reference,
// and the floors with where each came from (measured, minimum, capped or given).
#pragma once

#include "analysis/analysis.h"
#include "report/detail/canvas.h"

#include <string>
#include <vector>

namespace glint::detail {

/// What the footer names besides the run's numbers.
struct FooterInput {
    std::string reference_name;  ///< file name, or a description ("phantom sphere")
    std::string examined_name;
    std::string date;  ///< of the run, "2026-11-26 10:31 UTC"
};

/// The footer's lines: inputs and date; the fit (identity; or its rotation angle in degrees,
/// translation and, when registered, RMS with the unit); zoom 0's floors and their sources.
[[nodiscard]] std::vector<std::string> footer_lines(const AnalysisResult& result,
                                                    const FooterInput& input);

/// The current time as "YYYY-MM-DD HH:MM UTC".
[[nodiscard]] std::string utc_date_now();

/// Height of a footer of `lines` lines, pixels.
[[nodiscard]] int footer_height(std::size_t lines);

/// `sheet` with the footer below it (the sheet's width, footer_height(lines.size()) taller).
[[nodiscard]] Canvas with_footer(const Canvas& sheet, const std::vector<std::string>& lines);

}  // namespace glint::detail
