// One analysis pipeline: fit → signed distance → plan → sweep → decide → export.
//
// Every caller — `glint sweep`, `glint calibrate`, scenario runs — fills one AnalysisOptions
// and calls analyse(); nothing else assembles the pipeline. validate() checks every option
// before any mesh is loaded and names the bad one by its scenario key (OptionError::key),
// so a scenario file can point at its line.
//
//   reference ─┐
//   examined ──┴─▶ fit (scanner/fit.h) ─▶ fitted examined ─▶ signed distance (shape evidence)
//                                              │
//   plan (scanner/plan.h) ─▶ sweep (scanner/sweep.h): atlas + coverage per zoom
//                                              │
//   decide (scanner/decision.h) per zoom ─▶ floors + regions ─▶ exports (scanner/report.h)
#pragma once

#include "mesh/mesh.h"
#include "scanner/decision.h"
#include "scanner/fit.h"
#include "scanner/sweep.h"
#include "scanner/units.h"

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

/// One input of a run, for the report.
struct InputRecord {
    std::string role;            ///< "reference", "examined", "fit", "scenario", "calibration"
    std::filesystem::path path;  ///< empty for a generated mesh
    std::string description;     ///< e.g. "phantom condyle ico 5"
    std::size_t vertices = 0;
    std::size_t triangles = 0;
};

/// Which atlas files a run writes (all three by default): atlas.ply (MeshLab, CloudCompare,
/// Open3D), atlas.vtk (legacy ASCII: ParaView, 3D Slicer, CloudCompare), atlas.vtp (VTK XML:
/// ParaView, 3D Slicer). On a 2M-triangle mesh they are 129, 212 and 126 MB.
struct AtlasFiles {
    bool ply = true;
    bool vtk = true;
    bool vtp = true;
    [[nodiscard]] bool operator==(const AtlasFiles&) const = default;
};

/// "ply,vtp" → those files. \throw OptionError naming `key` for an unknown or repeated name or
/// an empty list.
[[nodiscard]] AtlasFiles parse_atlas_files(std::string_view list, const std::string& key);

/// "ply,vtk,vtp": the names of the files written, in that order.
[[nodiscard]] std::string to_string(const AtlasFiles& files);

struct ExportOptions {
    /// The output folder (written complete or not at all, scanner/output_folder.h); empty:
    /// nothing is written.
    std::filesystem::path output;
    bool write_views = true;  ///< per-view PNG heat maps
    /// Per-view EXR with the raw numbers (opt-in: a GPU sweep then reads every frame back).
    bool write_exr = false;
    AtlasFiles atlas_files;  ///< atlas.ply / atlas.vtk / atlas.vtp
    /// An existing output folder is replaced (atomically, when the run completes); false:
    /// it is refused before anything is loaded (--force).
    bool replace_existing = false;
    int mosaic_tile = 128;  ///< mosaic thumbnail size, pixels
    // Provenance recorded in report.json.
    std::string command_line;
    std::vector<InputRecord> inputs;
    std::vector<std::string> warnings;  ///< e.g. repairs done while loading
    /// Per-vertex scalars added to the atlas files as they are (e.g. a scenario's ground
    /// truth, "truth_damage" and "truth_distance", to be seen beside glint's own fields in a
    /// viewer); each holds one value per reference vertex.
    std::vector<std::pair<std::string, std::vector<float>>> extra_scalars;

    /// \throw OptionError; InputError when the output folder exists and may not be replaced.
    void validate() const;
};

struct AnalysisOptions {
    UnitOptions units;
    FitOptions fit;
    SweepOptions sweep;
    DecisionOptions decision;
    ExportOptions exports;

    /// Every option, before anything is loaded. \throw OptionError naming the key.
    void validate() const;
};

/// The options as JSON (report.json's "analysis"; two callers that mean the same run
/// produce the same text).
[[nodiscard]] std::string to_json(const AnalysisOptions& options);

struct AnalysisResult {
    FitOutcome fit;
    std::vector<float> distance;   ///< per reference vertex, signed (negative = loss)
    std::vector<float> tolerance;  ///< per reference vertex, tessellation tolerance (scanner/fit.h)
    std::vector<std::uint8_t>
        at_border;  ///< per reference vertex, closest examined point on a border
    SweepResult sweep;
    std::vector<ZoomDecision> decisions;  ///< one per zoom level
    double size = 0.0;                    ///< bounding diagonal of the reference (mesh units)
    std::string unit;              ///< of every length reported ("" = unknown; scanner/units.h)
    UnitResolution units;          ///< how the unit was found, both sizes
    std::filesystem::path output;  ///< the folder written (empty when none)
    std::vector<std::string> warnings;  ///< load, unit, fit and decision warnings
    /// Non-empty when REF and EXA look swapped (no region a loss, the examined surface
    /// > 10 % larger): a hint for people, also in warnings.
    std::string swap_hint;
    double fit_seconds = 0.0;
    double distance_seconds = 0.0;
    double decision_seconds = 0.0;
    double export_seconds = 0.0;
    double total_seconds = 0.0;
};

/// Progress of a long analysis; every member may be empty.
struct AnalysisObserver {
    std::function<void(std::string_view stage)>
        stage;  ///< "fit", "distance", "sweep", "decide", "export", "pictures"
    std::function<void(std::size_t done, std::size_t total)> views;
};

/// Runs the pipeline. The reference must have vertex normals (loaded meshes do). The examined
/// mesh is taken by value and fitted in place: a caller done with it moves it in, and the
/// largest meshes are not held twice.
/// \throw OptionError invalid options; InputError meshes whose sizes differ by more than
/// kMaxScaleRatio (unless allowed), a fit that did not converge, surfaces that do not overlap;
/// IoError, DeviceError; Cancelled (nothing half-written is left).
[[nodiscard]] AnalysisResult analyse(const Mesh& reference, Mesh examined,
                                     const AnalysisOptions& options,
                                     const AnalysisObserver& observer = {});

}  // namespace glint
