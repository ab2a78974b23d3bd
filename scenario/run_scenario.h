// Running a scenario end to end (fit, sweep, atlas) and scoring it against its ground truth.
#pragma once

#include "analysis/analysis.h"
#include "scanner/sweep.h"
#include "scenario/evaluate.h"
#include "scenario/pair_truth.h"
#include "scenario/scenario.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace glint {

struct ScenarioRunOptions {
    std::filesystem::path
        output_root;             ///< atlas folder = output_root / scenario name; empty = no export
    bool write_views = false;    ///< per-view PNG/EXR (mosaics, atlas and report always)
    bool write_pictures = true;  ///< false: no PNG at all, the image library never loaded
    /// Hears "load" (the scenario's surfaces read or made), then inspect()'s stages, items and
    /// views (report/inspect.h); its `view` and `fitted` members too.
    AnalysisObserver observer;
    std::string command_line;  ///< recorded in report.json
    bool replace_existing =
        false;         ///< an existing atlas folder of a scenario is replaced (--force)
    std::string unit;  ///< when given, wins over the scenario's `unit` (--unit)
    bool allow_scale_mismatch = false;  ///< --allow-scale-mismatch
};

/// What a run of `sc` writes: its [exports], with the run's --views added and --no-pictures
/// (pictures = false) obeyed; the output folder is left to the caller.
[[nodiscard]] ExportOptions scenario_exports(const Scenario& sc, bool views, bool pictures);

struct ScenarioOutcome {
    std::string name;
    std::filesystem::path file;
    bool skipped = false;
    std::string skip_reason;
    std::filesystem::path output;  ///< atlas folder (when exported)
    std::size_t reference_vertices = 0;
    std::size_t views = 0;
    std::size_t regions = 0;   ///< zoom 0
    std::string largest_kind;  ///< "dent"/"bump"/"" (zoom 0)
    /// The first listed region's kind, "surface gone" for a loss in a hole (zoom 0; "": none),
    /// its area (mesh units²) and volume (mesh units³, negative = lost).
    std::string first_kind;
    double first_area = 0.0;
    double first_volume = 0.0;
    double coverage = 0.0;       ///< zoom 0
    double compared = 0.0;       ///< zoom 0: compared / reference area (decision/comparison.h)
    double threshold_deg = 0.0;  ///< zoom 0
    std::optional<DetectionScore> score;  ///< when the scenario has ground truth
    std::optional<PoseError> pose;        ///< when the scenario knows the true pose
    std::optional<RegionTally>
        tally;  ///< false regions, damages detected (truth or true distances)
    /// The same pair decided by a plain distance threshold (|atlas distance| > threshold,
    /// connected components): what glint's decision is compared with.
    struct Baseline {
        double threshold = 0.0;
        DetectionScore score;
        RegionTally tally;
    };
    std::optional<Baseline> baseline;
    std::string fit_mode;
    /// asymmetry = true: the plane and the findings (scenario/asymmetry_scenario.h)
    std::optional<AsymmetryOutcome> asymmetry;
    double seconds = 0.0;
    std::vector<std::string> failures;  ///< [expect] entries that did not hold
    std::vector<std::string> warnings;  ///< the run's warnings (report.json's)
    [[nodiscard]] bool passed() const { return !skipped && failures.empty(); }
};

/// Builds, fits, sweeps and scores a scenario. Missing shared data → skipped (reason given).
/// \throw InputError / IoError / DeviceError for anything else that is wrong.
/// The first input file the scenario names that does not exist, or "". A file this user may
/// not reach is no missing data: IoError naming the folder in the way (issue 23 item 18).
[[nodiscard]] std::string missing_input(const Scenario& scenario);

[[nodiscard]] ScenarioOutcome run_scenario(const Scenario& scenario,
                                           const ScenarioRunOptions& options);

}  // namespace glint
