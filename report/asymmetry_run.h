// An asymmetry run with outputs (analysis/asymmetry.h): the surface swept against its mirror,
// the findings paired, and report.json's "asymmetry" object and the "asymmetry" atlas field
// added. One path for `glint asymmetry` (tools/command_asymmetry.cpp), glint.asymmetry()
// (python/asymmetry_bindings.cpp) and scenarios with asymmetry = true
// (scenario/asymmetry_scenario.h).
//
//   AnalysisOptions ─▶ take_asymmetry_options (the fit's loss, samples and fit ROI go to the
//                      plane; the pipeline's fit is none: the mirror is made in place)
//   mesh ─▶ prepare_asymmetry ─▶ plausible? ─▶ inspect_asymmetry ─▶ outputs + findings
#pragma once

#include "analysis/asymmetry.h"
#include "report/inspect.h"
#include "report/orientation.h"
#include "report/run_inputs.h"

#include <optional>
#include <string>
#include <vector>

namespace glint {

/// The asymmetry options of an analysis: its fit's registration options (loss, samples, fit
/// ROI) fit the plane, and the analysis is left with no fit (the mirror is in place);
/// `given_plane` is checked instead of fitted when set.
[[nodiscard]] AsymmetryOptions take_asymmetry_options(AnalysisOptions& analysis,
                                                      std::optional<SymmetryPlane> given_plane);

struct AsymmetryInspection {
    Inspection inspection;
    AsymmetryFindings findings;         ///< of zoom 0
    std::string json;                   ///< report.json's "asymmetry" object (JSON text)
    std::vector<std::string> warnings;  ///< the run's, less the "no fit requested" one
};

/// Sweeps `mesh` against `plane.mirror` (plausible: non-empty) with `options` (no fit, see
/// take_asymmetry_options) and writes the outputs with the findings added; the mirror is
/// recorded in `record` as the examined input.
/// \throw as inspect().
[[nodiscard]] AsymmetryInspection inspect_asymmetry(const Mesh& mesh, AsymmetryPlane plane,
                                                    InspectOptions options, RunRecord record,
                                                    const Orientation& orientation,
                                                    const AnalysisObserver& observer = {});

}  // namespace glint
