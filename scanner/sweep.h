// The rotary scan: render the reference and the fitted examined mesh from every view of a
// plan, compare view by view, fold the deviations onto the reference surface.
//
//   plan ─▶ for each view, band by band of rows as they are rendered (render_view_pair_rows):
//             reference rows ─┬─▶ compare (metric) ─▶ scatter samples     (on the workers)
//             examined rows  ─┘
//           then, the view whole: samples + gather ─▶ ZoomAtlas[z]        (per-vertex ranges)
//   ZoomAtlas[z] + ROI ─▶ coverage (seen mask)
//
// With Embree no frame is ever whole in memory: a worker traces a band of both frames and
// compares and scatters it while it is in cache; what stays per view are the maps the gather
// and the per-view exports read (ViewMaps, scanner/backproject.h). With Vulkan the frames are
// read back whole and handed on by bands. The atlas is the same either way, bit for bit.
//
// The decision (floors, regions) is decision/decision.h's; the whole pipeline (fit, distance,
// sweep, decision, exports) is analysis/analysis.h's.
#pragma once

#include "mesh/mesh.h"
#include "mesh/surface_index.h"
#include "render/frame.h"
#include "render/renderer.h"
#include "scanner/atlas.h"
#include "scanner/compare.h"
#include "scanner/coverage.h"
#include "scanner/metric.h"
#include "scanner/plan.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace glint {

/// Where a sweep compares frames and folds them onto the reference (scanner/gpu_sweep.h).
enum class Accumulation {
    Auto,  ///< on the GPU when the backend is Vulkan and the device can, else Host
    Gpu,   ///< on the GPU: frames never leave the device; a DeviceError when it cannot
    Host,  ///< frames read back and folded on the CPU (the reference the GPU path is tested against)
};

/// "auto" / "gpu" / "host". \throw InputError.
[[nodiscard]] Accumulation parse_accumulation(const std::string& text);
[[nodiscard]] std::string to_string(Accumulation accumulation);

struct SweepOptions {
    SweepPlanOptions plan;
    /// The deviation the atlas, the thresholds and the regions use (scanner/metric.h).
    Metric metric = Metric::AngleDeg;
    /// Backend, device, supersample (footprint averaging: s×s sub-samples per pixel).
    RenderOptions render{.supersample = 2};
    CompareOptions compare;
    double max_incidence_deg = 75.0;  ///< coverage rule (scanner/backproject.h)
    /// Compare and back-projection on the GPU (Auto, with Vulkan) or the CPU. The GPU path
    /// gives the same atlas within render/gpu_atlas.h's tolerances; its observer sees no frames.
    Accumulation accumulate = Accumulation::Auto;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

/// What one view showed (the view itself is SweepPlan::views[index]).
/// One view's numbers (render/atlas_totals.h, the same on both paths) and which view it was.
struct ViewSummary : ViewNumbers {
    int index = 0;
};

/// The atlas and coverage of one zoom level.
struct SweepZoom {
    ZoomAtlas atlas;
    Coverage coverage;
};

struct SweepResult {
    SweepPlan plan;
    SweepOptions options;  ///< as the sweep ran
    std::vector<SweepZoom> zooms;
    std::vector<ViewSummary> views;
    RendererInfo renderer;
    /// Whether compare and back-projection ran on the GPU; when not, accumulation_note says
    /// why (empty when the read-back path was asked for).
    bool on_gpu = false;
    std::string accumulation_note;
    /// Read-back path: rendering and comparison share the workers band by band, so
    /// compare_seconds is the comparison's share (compare + scatter summed over the workers and
    /// divided by their number, plus the per-view fold, gather and observer) and render_seconds
    /// the rest. GPU path: render_seconds is render, compare and back-projection on the device,
    /// compare_seconds reading the totals back.
    double render_seconds = 0.0;
    double compare_seconds = 0.0;
    double total_seconds = 0.0;
};

/// Called after each view with its deviation map (valid during the call; `value` holds the
/// metric): per-view exports, progress. May throw (Cancelled, IoError) to stop the sweep. On
/// the GPU path (SweepResult::on_gpu) nothing per pixel reaches the host: the map is empty
/// (0 x 0); ask for Accumulation::Host when an observer needs it.
using ViewObserver = std::function<void(const PlannedView& view, const DeviationMap& deviation)>;

/// \throw InputError when no view compared a single pixel (the surfaces do not overlap: a
/// wrong fit); both paths of run_sweep check it after the last view.
void require_overlap(const std::vector<ViewSummary>& views);

/// BVHs of the two surfaces the run built already (mesh/surface_index.h), for the CPU renderer;
/// a null one: the renderer builds its own.
struct SweepSurfaces {
    std::shared_ptr<const SurfaceIndex> reference;
    std::shared_ptr<const SurfaceIndex> examined;
};

/// Runs the sweep over `plan` (from make_sweep_plan(reference, options.plan)). `examined`
/// must already be in reference coordinates (fitted).
/// \throw InputError invalid options, an empty plan, a reference without normals, surfaces
/// that overlap in no view; DeviceError renderer trouble; Cancelled.
[[nodiscard]] SweepResult run_sweep(const Mesh& reference, const Mesh& examined,
                                    const SweepPlan& plan, const SweepOptions& options,
                                    const ViewObserver& observer = {},
                                    const SweepSurfaces& surfaces = {});

}  // namespace glint
