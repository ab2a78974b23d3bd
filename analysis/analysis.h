// One analysis pipeline: fit → signed distance → plan → sweep → decide. It writes no file:
// a run with outputs (output folder, atlas files, pictures, report.json) is report/inspect.h's.
//
// Every caller — `glint sweep`, `glint calibrate`, scenario runs, Python — fills one
// AnalysisOptions (its fields are declared once, in analysis/option_registry.h) and calls
// analyse(); nothing else assembles the pipeline. validate() checks every option before any
// mesh is loaded and names the bad one by its scenario key (OptionError::key), so a scenario
// file can point at its line.
//
//   reference ─┐
//   examined ──┴─▶ fit (analysis/fit.h) ─▶ fitted examined ─▶ signed distance (shape evidence)
//                                              │
//   plan (scanner/plan.h) ─▶ sweep (scanner/sweep.h): atlas + coverage per zoom
//                                              │
//   decide (decision/decision.h) per zoom ─▶ floors + regions
#pragma once

#include "analysis/fit.h"
#include "analysis/resolution.h"
#include "analysis/units.h"
#include "decision/decision.h"
#include "mesh/mesh.h"
#include "mesh/scan_view.h"
#include "mesh/surface_index.h"
#include "scanner/sweep.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

struct AnalysisOptions {
    UnitOptions units;
    FitOptions fit;
    SweepOptions sweep;
    DecisionOptions decision;

    /// Every option, before anything is loaded. \throw OptionError naming the key.
    void validate() const;
};

struct AnalysisResult {
    FitOutcome fit;
    std::vector<float> distance;  ///< per reference vertex, signed (negative = loss)
    std::vector<float>
        tolerance;  ///< per reference vertex, tessellation tolerance (analysis/fit.h)
    std::vector<std::uint8_t>
        at_border;  ///< per reference vertex, closest examined point on a border
    std::vector<std::uint8_t>
        facing_away;  ///< per reference vertex, closest examined triangle faces away
    /// The fitted examined surface's view when it is a one-view scan (mesh/scan_view.h), in
    /// the reference's frame: its dropouts at grazing incidence are not compared.
    std::optional<ScanView> scan_view;
    /// Per reference vertex, 1 where the fitted examined scan's field of view (its volume's
    /// grid and surface ROI: mesh/field_of_view.h) does not hold it, or holds it less than a
    /// voxel deep; empty where the field of view is unknown (a mesh file).
    std::vector<std::uint8_t> beyond_examined_view;
    /// The fitted examined surface encloses its solid (decision/comparison.h
    /// kMaxEnclosedBorder): surface it lacks, whatever its extent, is material gone.
    bool examined_encloses = false;
    /// Where the pair cannot compare because another sheet lies closer than the scans' voxels
    /// (analysis/resolution.h): empty for surfaces from mesh files.
    ResolutionEvidence resolution;
    /// The coarser scan's voxel, its longest edge (mesh units; 0: no grid known): the decision
    /// reads its evidence no finer (DecisionEvidence::voxel).
    double voxel = 0.0;
    SweepResult sweep;
    /// The reference's BVH the fit and the sweep shared (mesh/surface_index.h), kept for the
    /// pictures (report/) when the reference has at most kKeptIndexTriangles; null otherwise.
    std::shared_ptr<const SurfaceIndex> reference_index;
    std::vector<ZoomDecision> decisions;  ///< one per zoom level
    double size = 0.0;                    ///< bounding diagonal of the reference (mesh units)
    std::string unit;      ///< of every length reported ("" = unknown; analysis/units.h)
    UnitResolution units;  ///< how the unit was found, both sizes
    std::vector<std::string> warnings;  ///< unit, fit and decision warnings
    /// Non-empty when REF and EXA look swapped (no region a loss, the examined surface
    /// > 10 % larger): a hint for people, also in warnings.
    std::string swap_hint;
    double fit_seconds = 0.0;
    double distance_seconds = 0.0;
    double decision_seconds = 0.0;
    double total_seconds = 0.0;
};

/// A reference of at most this many triangles keeps its BVH for the pictures after the analysis
/// (AnalysisResult::reference_index). note: above it the BVH (113 MB compact at 2M triangles,
/// with its copy of the geometry 160 MB) would be held through the atlas files and the report
/// page, past the 600 MiB peak a 2M-triangle run keeps to; the pictures then build their own.
inline constexpr std::size_t kKeptIndexTriangles = 1'000'000;

/// Progress of a long analysis, and the sweep's views as they are compared; every member may
/// be empty.
struct AnalysisObserver {
    /// "fit", "distance", "sweep", "decide" (report/inspect.h adds the exports' stages).
    std::function<void(std::string_view stage)> stage;
    /// The sweep's views compared so far, of `total`.
    std::function<void(std::size_t done, std::size_t total)> views;
    /// Items done within the stage last announced, of `total`, for stages that count theirs
    /// (the exports: files written, pictures drawn); the sweep's views come through `views`.
    std::function<void(std::size_t done, std::size_t total)> items;
    /// The sweep's plan, once made and before its first view (a per-view store sizes itself).
    std::function<void(const SweepPlan& plan)> plan;
    /// Each view's deviation map while it is valid (per-view exports); on the GPU path the map
    /// is empty (scanner/sweep.h ViewObserver).
    ViewObserver view;
    /// The fitted examined mesh (reference coordinates, with the vertex normals the sweep
    /// rendered) and the result with its decisions, once decided and just before analyse()
    /// releases the mesh: report.html keeps a decimated copy for its live view
    /// (report/report_html.h live_examined).
    std::function<void(const Mesh& fitted, const AnalysisResult& result)> fitted;
};

/// Runs the pipeline. The reference must have vertex normals (loaded meshes do). The examined
/// mesh is taken by value and fitted in place: a caller done with it moves it in, and the
/// largest meshes are not held twice.
/// \throw OptionError invalid options; InputError meshes whose sizes differ by more than
/// kMaxScaleRatio (unless allowed), a fit that did not converge, surfaces that do not overlap;
/// IoError (a fit or landmarks file unreadable), DeviceError; Cancelled.
[[nodiscard]] AnalysisResult analyse(const Mesh& reference, Mesh examined,
                                     const AnalysisOptions& options,
                                     const AnalysisObserver& observer = {});

}  // namespace glint
