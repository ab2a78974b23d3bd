// The rotary scan end to end: render the reference and the fitted examined mesh from every
// view of a plan, compare view by view, fold the deviations onto the reference surface.
//
//   plan ─▶ for each view: reference frame ─┬─▶ compare ─▶ back-project ─▶ ZoomAtlas[z]
//                          examined frame  ─┘        (frames dropped after use)
//   ZoomAtlas[z] + seen mask ─▶ threshold (given, or noise floor) ─▶ regions per zoom
//
// Coverage rule: a reference vertex is *seen* when at least one pixel whose centre lies on
// one of its triangles (barycentric weight ≥ 1e-3) observed it at an incidence angle of at
// most `max_incidence_deg` (angle between the triangle normal and the direction to the
// camera). Unseen vertices are never declared undamaged: they are listed as unseen.
// A reference pixel with no examined surface behind it (silhouette change: surface missing)
// counts as a 90° deviation.
//
// Regions and the noise floor use the per-vertex *mean* angle: the angle between two
// surface normals does not depend on the view, so the mean over every observation is the
// estimate, and the maximum (kept in the atlas) mostly records the noisiest, most grazing
// pixel. With an ROI, only vertices inside it are analysed; the rest count as unseen.
#pragma once

#include "mesh/mesh.h"
#include "render/frame.h"
#include "render/renderer.h"
#include "scanner/atlas.h"
#include "scanner/compare.h"
#include "scanner/plan.h"
#include "scanner/regions.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace glint {

/// The per-pixel deviation folded onto the surface and thresholded into regions.
enum class Metric {
    AngleDeg,  ///< angle between the reference and examined normals, degrees (primary)
    RgbAbs,    ///< the paper's metric: mean |ΔR|,|ΔG|,|ΔB| of the 8-bit normal colours, 0…255
};
/// "angle" / "rgb". \throw InputError.
[[nodiscard]] Metric parse_metric(const std::string& text);
[[nodiscard]] std::string to_string(Metric metric);

struct SweepOptions {
    SweepPlanOptions plan;
    /// The deviation the atlas, the thresholds and the regions use. With RgbAbs every
    /// "deg" field below (threshold, noise floor, region angles) is in 8-bit colour units, and
    /// a reference pixel with no examined surface behind it counts 255 instead of 90°.
    Metric metric = Metric::AngleDeg;
    RenderOptions render;          ///< backend, device, supersample (footprint averaging)
    CompareOptions compare;
    double max_incidence_deg = 75.0;     ///< coverage rule (see file comment)
    std::optional<double> threshold_deg; ///< given: used as is for every zoom
    double noise_k = 6.0;                ///< auto threshold: median + k·1.4826·MAD …
    double min_threshold_deg = 2.0;      ///< … but never below this (see README)
    std::size_t min_region_vertices = 3;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

/// What one view showed.
struct ViewSummary {
    int index = 0;
    double azimuth_deg = 0.0;
    double elevation_deg = 0.0;
    int zoom_index = 0;
    int size = 0;
    std::size_t reference_pixels = 0;   ///< covered in the reference frame
    std::size_t compared = 0;
    std::size_t reference_only = 0;
    std::size_t examined_only = 0;
    double max_angle_deg = 0.0;
    double mean_angle_deg = 0.0;
};

/// Results of one zoom level.
struct ZoomResult {
    ZoomAtlas atlas;
    std::vector<std::uint8_t> seen;    ///< per vertex, coverage rule at this zoom
    double coverage = 0.0;             ///< seen area / total area
    NoiseFloor noise;                  ///< of angle_mean over seen vertices
    double threshold_deg = 0.0;        ///< used for the regions
    std::string threshold_rule;        ///< "given" or "noise floor: median + k·1.4826·MAD, min …"
    RegionResult regions;
    std::vector<std::size_t> histogram;    ///< angle_mean of seen vertices, 1° bins 0…89, ≥90
};

struct SweepResult {
    SweepPlan plan;
    SweepOptions options;  ///< as the sweep ran (for the report: enough to repeat the run)
    std::vector<ZoomResult> zooms;
    std::vector<ViewSummary> views;
    RendererInfo renderer;
    double render_seconds = 0.0;
    double compare_seconds = 0.0;
    double total_seconds = 0.0;
};

/// Called after each view with both frames and their deviation map (valid during the call):
/// exports per-view images, progress.
using ViewObserver = std::function<void(const PlannedView& view, const Frame& reference,
                                        const Frame& examined, const DeviationMap& deviation)>;

/// Runs the sweep over `plan` (from make_sweep_plan(reference, options.plan)). `examined`
/// must already be in reference coordinates (fitted).
/// \throw InputError invalid options, an empty plan, surfaces that overlap in no view;
/// DeviceError renderer trouble.
/// `distance` (optional, one per reference vertex, negative = loss) decides whether a
/// region is a dent or a bump; without it the signed depth difference does.
[[nodiscard]] SweepResult run_sweep(const Mesh& reference, const Mesh& examined, const SweepPlan& plan,
                                    const SweepOptions& options, const ViewObserver& observer = {},
                                    const std::vector<float>& distance = {});

/// Converts a planned view to the renderer's View.
[[nodiscard]] View to_render_view(const PlannedView& planned);

/// Frame → read-only view for compare_frames.
[[nodiscard]] FrameView frame_view(const Frame& frame);

}  // namespace glint
