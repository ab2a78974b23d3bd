// Command-line flags bound straight to AnalysisOptions fields (scanner/analysis.h), so the
// command line, scenario files and calibration share one set of defaults. Text flags (plan,
// metric, loss, ROI, backend, rule) are parsed while the command line is read: a bad value
// fails before any mesh is loaded.
#pragma once

#include "scanner/analysis.h"

#include <CLI/CLI.hpp>

namespace glint::cli {

/// How the examined mesh is fitted: --fit FILE | --register, with --loss, --fit-roi
/// (sphere:/box:/mask:FILE[:SCALAR]), --symmetric, --landmarks, --init, --samples,
/// --max-iterations, --no-coarse. `roi_flag` names the ROI flag ("--fit-roi" for sweep,
/// "--roi" for register); `with_mode` adds --fit and --register (a command that always
/// registers leaves them out).
void add_fit_flags(CLI::App& command, FitOptions& fit, const std::string& roi_flag,
                   bool with_mode = true);

/// The sweep and the decision: --plan, --azimuth-step, --elevations, --zoom, --roi, --size,
/// --supersample, --metric, --backend, --device, --max-incidence, --rule, --threshold-deg,
/// --noise-k, --min-threshold-deg, --shape-threshold, --min-region-vertices.
void add_sweep_flags(CLI::App& command, AnalysisOptions& options);

/// --unit (the unit both meshes are in; wins over what the files state) and
/// --allow-scale-mismatch (scanner/units.h).
void add_unit_flags(CLI::App& command, UnitOptions& units);

/// --print-options: print the resolved AnalysisOptions as JSON and stop, loading nothing.
void add_print_options_flag(CLI::App& command, bool& print);

/// Prints to_json(options) on stdout.
void print_options(const AnalysisOptions& options);

}  // namespace glint::cli
