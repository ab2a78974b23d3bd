// Running a scenario with asymmetry = true (scenario/asymmetry_scenario.h), and what it shares
// with the regular run (scenario/run_scenario.cpp). Internal.
#pragma once

#include "report/inspect.h"
#include "report/orientation.h"
#include "report/run_inputs.h"
#include "scenario/run_scenario.h"
#include "scenario/scenario.h"

#include <string>
#include <vector>

namespace glint::detail {

/// "phantom condyle ico 5", or "" for a mesh file.
[[nodiscard]] std::string describe_source(const SurfaceSource& source);

/// The space the reference's coordinates are in: a volume's surface is LPS (as ITK reads its
/// header), a mesh file says (SPACE=) or not, a phantom is in none.
[[nodiscard]] PatientSpace reference_space(const Scenario& sc);

/// The scenario's analysis options with the run's unit, its exports (output_root / name) and
/// the record of the scenario file and its reference (as input "reference").
[[nodiscard]] InspectOptions scenario_inspect_options(const Scenario& sc,
                                                      const ScenarioRunOptions& run,
                                                      const ScenarioMeshes& meshes,
                                                      RunRecord& record);

/// The examined surface (the one surface, derived from the reference) compared with its
/// mirror: fills `out` (its asymmetry, regions, coverage, and the score of the findings'
/// regions against the damage labels when the surface carries them) and returns the regions
/// of zoom 0 (none when no plane is plausible: then nothing is written).
/// \throw InputError a fit ROI with no surface inside, as glint asymmetry.
[[nodiscard]] std::vector<Region> run_asymmetry(const Scenario& sc, const ScenarioRunOptions& run,
                                                const ScenarioMeshes& meshes,
                                                InspectOptions options, RunRecord record,
                                                ScenarioOutcome& out);

}  // namespace glint::detail
