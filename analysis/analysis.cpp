#include "analysis/analysis.h"

#include "analysis/region_views.h"
#include "decision/comparison.h"
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/fault_injection.h"
#include "mesh/normals.h"
#include "mesh/scan_view.h"
#include "mesh/stopwatch.h"
#include "mesh/voxel_grid.h"
#include "mesh/winding.h"
#include "render/context.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <future>
#include <optional>
#include <system_error>

namespace glint {

namespace {

using Clock = std::chrono::steady_clock;

void announce(const AnalysisObserver& observer, std::string_view stage) {
    fault_point(stage);
    throw_if_cancelled();
    if (observer.stage) observer.stage(stage);
}

// The fit, refused when a registration did not converge: a sweep from a wrong pose would
// report the misfit as damage.
FitOutcome fit_or_refuse(const Mesh& reference, const Mesh& examined, const FitOptions& options,
                         const std::shared_ptr<const SurfaceIndex>& reference_index) {
    FitOutcome fit = fit_examined(reference, examined, options, reference_index);
    if (!fit.converged)
        throw InputError(
            "registration of the examined mesh onto the reference did not converge (" +
            (fit.warnings.empty() ? std::string("no reason given") : fit.warnings.back()) +
            "); the meshes may not overlap: give a fit file or start from landmarks (glint register)");
    return fit;
}

// Whether the sweep renders on the CPU (Embree), where it casts into the run's BVHs; a device
// that failed to open is left for the sweep to report.
bool sweeps_on_cpu(const RenderOptions& render) {
    try {
        return shared_render_context(render.context_options())->backend() == Backend::Embree;
    } catch (const std::exception&) {
        return false;
    }
}

// The plan's ROI with its mask read (a sweep ROI may be a vertex mask file).
SweepPlanOptions resolved_plan(const SweepPlanOptions& plan, std::size_t vertex_count) {
    SweepPlanOptions p = plan;
    if (p.roi && p.roi->needs_mask()) read_roi_mask(*p.roi, vertex_count);
    return p;
}

// A reference and examined given the wrong way round (the intact surface as EXA, the
// resected one as REF): the examined has surface the reference lacks, which the atlas on the
// reference cannot show as a loss: no region, or gains only. Only a hint (a growth can look
// the same), given when the examined surface is 10 % larger and no region at zoom 0 is a
// loss. note: 10 % because two scans of one surface differ by a few %.
std::string swap_hint(const Mesh& reference, double exa_area, const AnalysisResult& result) {
    if (result.decisions.empty()) return "";
    for (const auto& r : result.decisions[0].regions.regions)
        if (r.kind != RegionKind::Bump) return "";
    const double ref_area = surface_area(reference);
    if (!(exa_area > 1.1 * ref_area)) return "";
    char b[240];
    std::snprintf(
        b, sizeof b,
        "the examined surface is %.0f%% larger than the reference and no region is a loss: "
        "are REF and EXA swapped? (REF is the surface before, EXA the one examined)",
        100.0 * (exa_area / ref_area - 1.0));
    return b;
}

// Per reference vertex, whether the fitted examined scan's field of view fails to hold it a
// voxel deep (empty: unknown). note: a voxel — marching cubes places the examined surface up to
// its outer voxels' centres, and its last row of triangles there curls.
std::vector<std::uint8_t> beyond_view(const Mesh& reference, const Mesh& fitted) {
    if (fitted.field_of_view.empty()) return {};
    const double voxel = fitted.voxel_axes ? fitted.voxel_axes->colwise().norm().maxCoeff() : 0.0;
    std::vector<std::uint8_t> beyond(reference.vertex_count(), 0);
    for (std::size_t v = 0; v < beyond.size(); ++v)
        beyond[v] = fitted.field_of_view.depth_inside(reference.positions[v].cast<double>()) < voxel
                        ? 1
                        : 0;
    return beyond;
}

// The sweep of the fitted pair, each view handed to the observer on the way.
void sweep_step(const Mesh& reference, const Mesh& fitted, const AnalysisOptions& options,
                const AnalysisObserver& observer, const SweepSurfaces& surfaces,
                AnalysisResult& result) {
    const SweepPlan plan =
        make_sweep_plan(reference, resolved_plan(options.sweep.plan, reference.vertex_count()));
    if (observer.plan) observer.plan(plan);
    std::size_t done = 0;
    result.sweep = run_sweep(
        reference, fitted, plan, options.sweep,
        [&](const PlannedView& v, const DeviationMap& d) {
            if (observer.view) observer.view(v, d);
            if (observer.views) observer.views(++done, plan.views.size());
        },
        surfaces);
}

// One decision per zoom from the atlas and the shape evidence; their warnings named by zoom.
void decide_step(const Mesh& reference, const AnalysisOptions& options, AnalysisResult& result) {
    for (const auto& zoom : result.sweep.zooms) {
        const DecisionEvidence evidence{
            .atlas = &zoom.atlas,
            .coverage = &zoom.coverage,
            .distance = &result.distance,
            .tolerance = &result.tolerance,
            .at_border = &result.at_border,
            .facing_away = &result.facing_away,
            .scan_view = result.scan_view ? &*result.scan_view : nullptr,
            .below_resolution = &result.resolution.below,
            .beyond_view = &result.beyond_examined_view,
            .examined_encloses = result.examined_encloses,
            .sampling = &result.resolution.sampling,
            .voxel = result.voxel,
            .metric = options.sweep.metric,
            .size = result.size,
            .unit = result.unit};
        result.decisions.push_back(decide(reference, evidence, options.decision));
        if (!result.resolution.rule.empty())
            result.decisions.back().comparison.rule += "; " + result.resolution.rule;
        for (const auto& w : result.decisions.back().warnings)
            result.warnings.push_back("zoom " + std::to_string(result.decisions.size() - 1) + ": " +
                                      w);
    }
}

}  // namespace

namespace {

// An open surface faces inward when its outward score (mesh/winding.h) is below -kInsideOut
// while its pair's is above +kInsideOut: the open patches of the evaluation score 0.5-0.8
// facing outward (a condyle crop, teeth, range scans). A closed one faces inward whenever its
// score is below -kClosedInsideOut: its score is 3 × its enclosed volume over its spread, so
// its sign is the answer, small as it may be for thin shapes (the CBCT jaw scores +0.21).
constexpr double kInsideOut = 0.3;

// The largest --resolution, in sizes of the reference (its bounding-box diagonal).
constexpr double kMaxResolutionSizes = 1000.0;
constexpr double kClosedInsideOut = 0.01;

struct InsideOut {
    bool reference = false;  ///< the reference must be turned (the examined is turned here)
    std::vector<std::string> warnings;
};

// Turns the examined surface when it is inside out; says whether the reference must be.
InsideOut turn_inside_out_inputs(const Mesh& reference, Mesh& examined) {
    InsideOut out;
    const double r = outward_score(reference), e = outward_score(examined);
    const auto inside_out = [](const Mesh& m, double own, double other) {
        return (own <= -kInsideOut && other >= kInsideOut) ||
               (own <= -kClosedInsideOut && is_closed(m));
    };
    const auto said = [&](const char* which, double own, double other, const char* what) {
        char text[400];
        std::snprintf(text, sizeof text,
                      "the %s surface is inside out (its triangles are wound clockwise seen from "
                      "outside: outward score %+.2f, the other surface's %+.2f): turned for the "
                      "analysis, so that dents and bumps keep their sign%s",
                      which, own, other, what);
        return std::string(text);
    };
    if (inside_out(examined, e, r)) {
        reverse_winding(examined);
        out.warnings.push_back(said("examined", e, r, ""));
    }
    if (inside_out(reference, r, e)) {
        out.reference = true;
        out.warnings.push_back(
            said("reference", r, e, "; the atlas files carry its triangles turned"));
    }
    return out;
}

}  // namespace

AnalysisResult analyse(const Mesh& reference_in, Mesh examined, const AnalysisOptions& options,
                       const AnalysisObserver& observer) {
    const auto t_start = Clock::now();
    options.validate();
    std::optional<Mesh> with_normals;
    if (!reference_in.has_normals()) {
        with_normals = reference_in;
        compute_vertex_normals(*with_normals);
    }
    AnalysisResult result;
    // Inside-out inputs (issue 53): a surface whose triangles are all wound the other way (as
    // some STL exporters write them) has every normal reversed; the fit found no compatible
    // pairs and a dent would read as a bump. It is turned for the analysis, and said so.
    {
        const Mesh& ref = with_normals ? *with_normals : reference_in;
        const InsideOut turned = turn_inside_out_inputs(ref, examined);
        if (turned.reference) {
            if (!with_normals) with_normals = reference_in;
            reverse_winding(*with_normals);
        }
        result.warnings = turned.warnings;
    }
    const Mesh& reference = with_normals ? *with_normals : reference_in;
    // Units and sizes, checked before the long work.
    result.units = resolve_units(reference, examined, options.units);
    result.unit = result.units.unit;
    if (result.units.examined_scale != 1.0) scale_to_analysis_unit(examined, result.units);
    result.size = bounds(reference).diagonal();
    result.warnings.insert(result.warnings.begin(), result.units.warnings.begin(),
                           result.units.warnings.end());
    // A mesh file exported from a CT segmentation without smoothing tells the grid it was
    // extracted on (mesh/voxel_grid.h): it is then read as the volume's surface would be, thin
    // plates and gaps below that grid not compared (issue 50). --resolution overrides.
    // A smoothed export keeps its grid's period (lattice_of_vertices).
    std::optional<Eigen::Matrix3d> reference_grid;
    bool examined_grid_detected = false, reference_smoothed = false, examined_smoothed = false;
    if (!options.decision.resolution) {
        if (!reference.voxel_axes)
            if (const auto g = detect_voxel_grid(reference)) {
                reference_grid = Eigen::Matrix3d(g->spacing.asDiagonal());
                reference_smoothed = g->smoothed;
            }
        if (!examined.voxel_axes)
            if (const auto g = detect_voxel_grid(examined)) {
                examined.voxel_axes = Eigen::Matrix3d(g->spacing.asDiagonal());
                examined_grid_detected = true;
                examined_smoothed = g->smoothed;
                // Where the volume's edge cut it: beyond, the scan saw nothing (not a loss).
                if (examined.field_of_view.empty())
                    examined.field_of_view = field_of_view_of_cut(examined, *g);
            }
    }
    // Bounded before any ray exists: a resolution of 1e38 put the below-resolution rays'
    // origins beyond what Embree accepts (it aborted, issue 52). A voxel larger than the
    // surface is meaningful (nothing is compared, and the run says so); one over 1000 times
    // its size is a number gone wrong.
    if (const auto& r = options.decision.resolution;
        r && !(*r <= kMaxResolutionSizes * result.size))
        throw OptionError("decision.resolution", *r,
                          "must be at most 1000 times the reference's size (its bounding-box "
                          "diagonal is " +
                              std::to_string(result.size) + " mesh units)");
    // The render device is opened while the fit runs: choosing it loads the Vulkan drivers
    // (lavapipe brings LLVM), 0.05-0.1 s on a CPU machine and more where a GPU starts. The
    // sweep takes the same shared context (render/context.h); a failure here is left for the
    // sweep to report.
    const auto open_device = [render = options.sweep.render.context_options()] {
        try {
            (void)shared_render_context(render);
        } catch (const std::exception&) {
        }
    };
    std::future<void> device;
    try {
        device = std::async(std::launch::async, open_device);
    } catch (const std::system_error&) {
        // No thread to be had: the sweep opens the device itself when it starts.
    }
    // One BVH per surface for the run (mesh/surface_index.h), shared by the fit, the distance,
    // the sweep's CPU renderer and (small enough) the pictures: the reference's is built for a
    // registration, or below for an Embree sweep; the fitted examined mesh's for the distance.
    std::shared_ptr<const SurfaceIndex> reference_index;
    announce(observer, "fit");
    auto t = Clock::now();
    if (options.fit.mode == FitMode::Register) reference_index = index_surface(reference);
    FitOptions fit_options = options.fit;
    // Sizes apart beyond kMaxScaleRatio (allowed by --allow-scale-mismatch) and no unit to say
    // by how much: a similarity fit starts from the ratio of the sizes (issue 53).
    if (fit_options.registration.fit_scale)
        fit_options.registration.initial_scale *= starting_scale(result.units);
    result.fit = fit_or_refuse(reference, examined, fit_options, reference_index);
    for (const auto& w : result.fit.warnings) result.warnings.push_back(w);
    // The examined mesh becomes the fitted one in place (it is this call's own copy), at the
    // fit's scale when it has one.
    Mesh& fitted = examined;
    apply_fit(fitted, result.fit);
    const double examined_area = surface_area(fitted);
    result.fit_seconds = seconds_since(t);

    announce(observer, "distance");
    t = Clock::now();
    std::shared_ptr<const SurfaceIndex> examined_index = index_surface(fitted);
    ShapeEvidence shape = measure_shape(reference, fitted, examined_index);
    result.distance = std::move(shape.distance);
    result.tolerance = std::move(shape.tolerance);
    result.at_border = std::move(shape.at_border);
    result.facing_away = std::move(shape.facing_away);
    result.scan_view = one_view_scan(fitted);
    result.beyond_examined_view = beyond_view(reference, fitted);
    result.examined_encloses = !result.scan_view && encloses(fitted);
    ResolutionGrids grids = resolution_grids(reference, fitted, options.decision.resolution);
    grids.examined_detected = examined_grid_detected;
    grids.examined_smoothed = examined_smoothed;
    if (!grids.reference && reference_grid) {
        grids.reference = reference_grid;
        grids.reference_detected = true;
        grids.reference_smoothed = reference_smoothed;
    }
    if (grids.reference || grids.examined) {
        for (const auto& grid : {grids.reference, grids.examined})
            if (grid) result.voxel = std::max(result.voxel, grid->colwise().norm().maxCoeff());
        if (!reference_index) reference_index = index_surface(reference);
        result.resolution =
            below_resolution(reference, fitted, grids, reference_index, examined_index);
    }
    result.distance_seconds = seconds_since(t);

    announce(observer, "sweep");
    if (device.valid()) device.wait();
    SweepSurfaces surfaces;
    if (sweeps_on_cpu(options.sweep.render)) {
        if (!reference_index) reference_index = index_surface(reference);
        surfaces = {reference_index, examined_index};
    }
    sweep_step(reference, fitted, options, observer, surfaces, result);
    // The examined BVH is not needed after the sweep (memory for the exports); the fitted copy
    // itself lives through the decision (below).
    surfaces = {};
    examined_index.reset();
    if (reference.triangle_count() <= kKeptIndexTriangles)
        result.reference_index = std::move(reference_index);

    announce(observer, "decide");
    t = Clock::now();
    decide_step(reference, options, result);
    // Each region's views: the sweep view and the direction all round that see the most of it
    // face on and unoccluded (analysis/region_views.h).
    {
        std::shared_ptr<const SurfaceIndex> index =
            result.reference_index ? result.reference_index : reference_index;
        for (std::size_t k = 0; k < result.decisions.size(); ++k) {
            RegionResult& found = result.decisions[k].regions;
            if (found.regions.empty()) continue;
            if (!index) index = index_surface(reference);
            choose_region_views(reference, index, result.sweep.plan, static_cast<int>(k),
                                found.region_of_vertex, found.regions);
        }
    }
    result.decision_seconds = seconds_since(t);
    // note: the fitted copy lives through the decision (its regions say which part of it a
    // decimated copy keeps whole); it is released before the exports, which need the memory.
    if (observer.fitted) observer.fitted(fitted, result);
    fitted = Mesh{};
    result.swap_hint = swap_hint(reference, examined_area, result);
    if (!result.swap_hint.empty()) result.warnings.push_back(result.swap_hint);

    result.total_seconds = seconds_since(t_start);
    return result;
}

}  // namespace glint
