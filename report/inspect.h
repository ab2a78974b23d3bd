// A run with outputs: analyse() (analysis/analysis.h) and everything around it that touches
// files: the output folder, per-view exports, atlas files, pictures, report.json and
// report.html. Every front end (glint sweep, the Slicer module, Python, scenarios) runs an
// inspection through inspect(); nothing else assembles the outputs.
//
//   RunRecord (report/run_inputs.h) ─┐
//   reference, examined ─────────────┴▶ analyse ─▶ atlas files, regions.csv, report.json
//                                        │ views   (report/report.h), pictures, report.html
//                                        ▼
//                                   views/*.exr (report/view_exports.h)
//
// The output folder appears complete or not at all (report/output_folder.h); it is checked
// before anything is analysed.
#pragma once

#include "analysis/analysis.h"
#include "mesh/mesh.h"
#include "report/export_options.h"
#include "report/run_inputs.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint {

/// What a command adds to a run's outputs once the analysis is known (glint asymmetry): atlas
/// fields after glint's own (as ExportOptions::extra_scalars) and one object of report.json.
struct ReportAddition {
    std::vector<std::pair<std::string, std::vector<float>>> scalars;
    std::string key;   ///< report.json's key for `json` ("" = none)
    std::string json;  ///< JSON text
    /// The examined surface is the reference's mirror about this plane: every output (report.json's
    /// regions, regions.csv, the atlas, the pictures) gives this side against the mirrored other
    /// side (analysis/asymmetry.h as_side_against_mirror), atlas.png draws the plane.
    std::optional<MirrorPictures> mirror;
};

struct InspectOptions {
    AnalysisOptions analysis;
    ExportOptions exports;
    /// Called once after the analysis, before anything is written; empty: nothing is added.
    std::function<ReportAddition(const AnalysisResult&)> addition;
    /// Every option, before anything is loaded. \throw OptionError naming the key; InputError
    /// an output folder that exists and may not be replaced.
    void validate() const;
};

struct Inspection {
    AnalysisResult analysis;       ///< warnings: the run record's, then the analysis'
    std::filesystem::path output;  ///< the folder written (empty when none)
    std::string report_json;       ///< report.json's text (made also when nothing is written)
    std::optional<Mesh> atlas;     ///< the atlas mesh, with ExportOptions::keep_atlas
    double export_seconds = 0.0;
    double total_seconds = 0.0;  ///< the whole inspection, exports included
};

/// Analyses the pair and writes the outputs. `observer` also hears "export" (report.json's
/// text, the inputs' checksums) and, with an output folder, write_outputs' stages and items
/// (report/report.h).
/// \throw as analyse(); InputError an output folder that exists and may not be replaced;
/// IoError writing; Cancelled (nothing half-written is left).
[[nodiscard]] Inspection inspect(const Mesh& reference, Mesh examined,
                                 const InspectOptions& options, const RunRecord& record,
                                 const AnalysisObserver& observer = {});

}  // namespace glint
