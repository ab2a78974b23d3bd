// Keyword arguments of the Python functions → glint's option structs.
//
// The analysis and export keywords are generated from the option registry
// (analysis/option_registry.h): one keyword per option, with its type, range and choices
// checked as the command line checks them, and documented in help() with its default and unit.
// A keyword left out keeps the library's default (there are no defaults in Python to drift from
// C++). The surface keywords (iso, …) are those of volume/surface.h.
#pragma once

#include "analysis/analysis.h"
#include "analysis/option_registry.h"
#include "report/export_options.h"
#include "volume/surface.h"

#include <pybind11/pybind11.h>

#include <string>

namespace glint::python {

/// What keywords can set.
struct Keywords {
    AnalysisOptions analysis;
    ExportOptions exports;
    SurfaceOptions surface;
    bool force = false;  ///< replace an existing output folder
};

/// Which keywords a function accepts: the registry's groups (kUnitGroup, kFitGroup,
/// kSweepGroup, kDecisionGroup, kExportGroup), and these.
/// iso, surface_roi, largest, seed, smooth, passband, edge, tolerance
inline constexpr unsigned kSurfaceKeywords = 1u << 8;
/// force
inline constexpr unsigned kForceKeyword = 1u << 9;

/// Every keyword of `analyse()`.
inline constexpr unsigned kAllKeywords = kUnitGroup | kFitGroup | kSweepGroup | kDecisionGroup |
                                         kExportGroup | kSurfaceKeywords | kForceKeyword;

/// Applies `kwargs` to `into`. \throw pybind11::type_error for a keyword the function does not
/// take (naming the ones it does); InputError naming the keyword for a value of the wrong type
/// or one its parser refuses.
void apply_keywords(Keywords& into, const pybind11::kwargs& kwargs, unsigned groups,
                    const std::string& function);

/// The keywords of `groups`, comma-separated (for errors).
[[nodiscard]] std::string keyword_names(unsigned groups);

/// The keywords of `groups`, one per line with its type, default, unit and help (docstrings).
[[nodiscard]] std::string keyword_docs(unsigned groups);

/// The keywords of `groups` as the keyword part of a Python signature ("size=512, …, force=False"),
/// each with its default as a literal (None where the default is not one: the library's).
[[nodiscard]] std::string keyword_signature(unsigned groups);

/// The keyword of the registry option at `path` ("sweep.size" → "size"); "" when none is.
[[nodiscard]] std::string keyword_of_option(const std::string& path);

/// The resolved options as the JSON --print-options prints (glint.options()).
[[nodiscard]] std::string options_json(const Keywords& keywords);

}  // namespace glint::python
