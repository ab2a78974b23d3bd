// The analysis options' table (analysis/option_registry.h): one declaration per option, bound to
// its field of AnalysisOptions. Adding an option is one entry here; every front end follows.
#include "analysis/analysis.h"
#include "analysis/option_fields.h"
#include "analysis/option_registry.h"
#include "mesh/roi.h"
#include "mesh/units.h"
#include "registration/icp.h"
#include "render/context.h"
#include "scanner/metric.h"
#include "scanner/plan.h"

#include <string>
#include <utility>
#include <vector>

namespace glint {

namespace {

using Field = OptionField<AnalysisOptions>;
using F = OptionFields<AnalysisOptions>;

std::vector<std::string> metric_names() {
    std::vector<std::string> out;
    for (const auto& m : metrics()) out.emplace_back(m.name);
    return out;
}

std::vector<std::string> unit_names() {
    std::vector<std::string> out;
    const std::string all = known_units();
    for (std::size_t start = 0; start < all.size();) {
        std::size_t comma = all.find(", ", start);
        if (comma == std::string::npos) comma = all.size();
        out.push_back(all.substr(start, comma - start));
        start = comma + 2;
    }
    return out;
}

std::string plan_text(const SweepPlanOptions& p) {
    return p.kind == SweepPlanOptions::Kind::Rotary ? "rotary"
                                                    : "sphere:" + std::to_string(p.sphere_views);
}

std::vector<Field> unit_fields() {
    return {
        F::text(
            {.name = "unit",
             .section = "",
             .key = "unit",
             .slicer = "unit",
             .group = kUnitGroup,
             .label = "Length unit",
             .help = "Length unit of both meshes (default: what the files state; unknown lengths "
                     "are printed as 'units')",
             .choices = unit_names()},
            OptionKind::Choice,
            [](const AnalysisOptions& o) { return F::text_or_unset(o.units.unit); },
            [](AnalysisOptions& o, const std::string& v) { o.units.unit = v; },
            [](AnalysisOptions& o) { o.units.unit.clear(); }),
        F::flag(
            {.name = "allow_scale_mismatch",
             .section = "",
             .key = "allow_scale_mismatch",
             .slicer = "allowScaleMismatch",
             .group = kUnitGroup,
             .label = "Allow scale mismatch",
             .help = "Run even when the meshes' sizes differ by more than 5x (different units?)"},
            [](auto& o) -> auto& { return o.units.allow_scale_mismatch; }),
    };
}

std::vector<Field> fit_fields() {
    return {
        F::text(
            {.name = "loss",
             .section = "registration",
             .key = "loss",
             .slicer = "loss",
             .group = kFitGroup,
             .label = "Robust loss",
             .help = "Registration: robust loss (damage must not pull the fit)",
             .choices = {"cauchy", "huber", "tukey", "none"}},
            OptionKind::Choice,
            [](const AnalysisOptions& o) -> OptionValue {
                return to_string(o.fit.registration.loss);
            },
            [](AnalysisOptions& o, const std::string& v) {
                o.fit.registration.loss = parse_loss(v);
            }),
        F::text(
            {.name = "fit_roi",
             .section = "registration",
             .key = "roi",
             .slicer = "fitRoi",
             .group = kFitGroup,
             .label = "Fit region",
             .help = "Registration: fit only on this stable region of the reference: "
                     "sphere:x,y,z,r, box:x0,y0,z0,x1,y1,z1 or mask:FILE.ply[:SCALAR]"},
            OptionKind::Region,
            [](const AnalysisOptions& o) -> OptionValue {
                return o.fit.registration.roi ? OptionValue(to_string(*o.fit.registration.roi))
                                              : OptionValue();
            },
            [](AnalysisOptions& o, const std::string& v) { o.fit.registration.roi = parse_roi(v); },
            [](AnalysisOptions& o) { o.fit.registration.roi.reset(); }),
        F::flag(
            {.name = "symmetric",
             .section = "registration",
             .key = "symmetric",
             .slicer = "symmetric",
             .group = kFitGroup,
             .label = "Symmetric ICP",
             .help = "Registration: symmetric ICP (both directions)"},
            [](auto& o) -> auto& { return o.fit.registration.symmetric; }),
        F::flag(
            {.name = "fit_scale",
             .section = "registration",
             .key = "fit_scale",
             .slicer = "fitScale",
             .group = kFitGroup,
             .label = "Fit the scale",
             .help = "Registration: also fit one scale factor of the examined surface (scanners "
                     "calibrated apart; a similarity fit), reported with its uncertainty"},
            [](auto& o) -> auto& { return o.fit.registration.fit_scale; }),
        F::flag(
            {.name = "coarse",
             .section = "registration",
             .key = "coarse",
             .slicer = "coarse",
             .group = kFitGroup,
             .label = "Coarse alignment",
             .help = "Registration: try the principal-axes hypotheses first (--no-coarse skips "
                     "them)"},
            [](auto& o) -> auto& { return o.fit.registration.coarse; }),
        F::integer(
            {.name = "samples",
             .section = "registration",
             .key = "samples",
             .slicer = "samples",
             .group = kFitGroup,
             .min = 50,
             .max = 10'000'000,
             .label = "Samples",
             .help = "Registration: samples on the examined surface"},
            [](auto& o) -> auto& { return o.fit.registration.samples; }),
        F::integer(
            {.name = "max_iterations",
             .section = "registration",
             .key = "max_iterations",
             .slicer = "maxIterations",
             .group = kFitGroup,
             .min = 1,
             .max = 10'000,
             .label = "ICP iterations",
             .help = "Registration: ICP iterations at most"},
            [](auto& o) -> auto& { return o.fit.registration.max_iterations; }),
        F::integer(
            {.name = "fit_seed",
             .section = "registration",
             .key = "seed",
             .slicer = "fitSeed",
             .group = kFitGroup,
             .min = 0,
             .max = 4294967295.0,
             .label = "Sampling seed",
             .help = "Registration: the seed of the surface sampling (a fit is repeatable for "
                     "a seed)"},
            [](auto& o) -> auto& { return o.fit.registration.seed; }),
        F::text(
            {.name = "landmarks",
             .section = "registration",
             .key = "landmarks",
             .slicer = "landmarks",
             .group = kFitGroup,
             .label = "Landmarks",
             .help = "Registration: start from landmark pairs (JSON: {\"pairs\": [{\"examined\": "
                     "SIDE, \"reference\": SIDE}]}, SIDE = [x,y,z] or a picked pixel)"},
            OptionKind::Path,
            [](const AnalysisOptions& o) {
                return F::text_or_unset(o.fit.landmarks_file.string());
            },
            [](AnalysisOptions& o, const std::string& v) { o.fit.landmarks_file = v; },
            [](AnalysisOptions& o) { o.fit.landmarks_file.clear(); }),
        F::text(
            {.name = "init",
             .section = "registration",
             .key = "init",
             .slicer = "init",
             .group = kFitGroup,
             .label = "Initial pose",
             .help = "Registration: start from this fit.json"},
            OptionKind::Path,
            [](const AnalysisOptions& o) { return F::text_or_unset(o.fit.init_file.string()); },
            [](AnalysisOptions& o, const std::string& v) { o.fit.init_file = v; },
            [](AnalysisOptions& o) { o.fit.init_file.clear(); }),
    };
}

std::vector<Field> plan_fields() {
    return {
        F::text(
            {.name = "plan",
             .section = "sweep",
             .key = "plan",
             .slicer = "plan",
             .group = kSweepGroup,
             .label = "Plan",
             .help = "rotary (azimuth steps x elevation rings) or sphere:N (N views spread over "
                     "the sphere)"},
            OptionKind::Text,
            [](const AnalysisOptions& o) -> OptionValue { return plan_text(o.sweep.plan); },
            [](AnalysisOptions& o, const std::string& v) { parse_plan_kind(v, o.sweep.plan); }),
        F::number(
            {.name = "azimuth_step",
             .section = "sweep",
             .key = "azimuth_step",
             .slicer = "azimuthStep",
             .group = kSweepGroup,
             .unit = "deg",
             .min = 0,
             .max = 360,
             .min_exclusive = true,
             .label = "Azimuth step",
             .help = "Rotary: angle between two views around the surface"},
            [](auto& o) -> auto& { return o.sweep.plan.azimuth_step_deg; }),
        F::numbers(
            {.name = "elevations",
             .section = "sweep",
             .key = "elevations",
             .slicer = "elevations",
             .group = kSweepGroup,
             .unit = "deg",
             .min = -90,
             .max = 90,
             .label = "Elevations",
             .help = "Rotary: elevation rings"},
            [](auto& o) -> auto& { return o.sweep.plan.elevations_deg; }),
        F::numbers(
            {.name = "zoom",
             .section = "sweep",
             .key = "zoom",
             .slicer = "zoom",
             .group = kSweepGroup,
             .unit = "mesh units/px",
             .min = 0,
             .min_exclusive = true,
             .label = "Zoom levels",
             .help = "Zoom levels as footprints (mesh units per pixel); none: frame the whole "
                     "surface in `size` pixels"},
            [](auto& o) -> auto& { return o.sweep.plan.footprints; }),
        F::text(
            {.name = "roi",
             .section = "sweep",
             .key = "roi",
             .slicer = "roi",
             .group = kSweepGroup,
             .label = "Analysed region",
             .help = "Analyse part of the surface: sphere:x,y,z,r, box:x0,y0,z0,x1,y1,z1 or "
                     "mask:FILE.ply[:SCALAR]"},
            OptionKind::Region,
            [](const AnalysisOptions& o) -> OptionValue {
                return o.sweep.plan.roi ? OptionValue(to_string(*o.sweep.plan.roi)) : OptionValue();
            },
            [](AnalysisOptions& o, const std::string& v) { o.sweep.plan.roi = parse_roi(v); },
            [](AnalysisOptions& o) { o.sweep.plan.roi.reset(); }),
        F::integer(
            {.name = "size",
             .section = "sweep",
             .key = "size",
             .slicer = "size",
             .group = kSweepGroup,
             .unit = "px",
             .min = 8,
             .max = 4096,
             .label = "Image size",
             .help = "Image size framing the whole surface (when no zoom is given)"},
            [](auto& o) -> auto& { return o.sweep.plan.size; }),
        F::number(
            {.name = "margin",
             .section = "sweep",
             .key = "margin",
             .slicer = "margin",
             .group = kSweepGroup,
             .min = 1,
             .max = 10,
             .label = "Framing margin",
             .help = "Framed radius = margin x the surface's bounding radius"},
            [](auto& o) -> auto& { return o.sweep.plan.margin; }),
    };
}

std::vector<Field> render_fields() {
    return {
        F::integer(
            {.name = "supersample",
             .section = "sweep",
             .key = "supersample",
             .slicer = "supersample",
             .group = kSweepGroup,
             .min = 1,
             .max = 8,
             .label = "Supersampling",
             .help = "s x s sub-samples per pixel (footprint averaging)"},
            [](auto& o) -> auto& { return o.sweep.render.supersample; }),
        F::text(
            {.name = "metric",
             .section = "sweep",
             .key = "metric",
             .slicer = "metric",
             .group = kSweepGroup,
             .label = "Metric",
             .help = "angle: degrees between the normals; rgb: the paper's 8-bit colour "
                     "difference",
             .choices = metric_names()},
            OptionKind::Choice,
            [](const AnalysisOptions& o) -> OptionValue { return to_string(o.sweep.metric); },
            [](AnalysisOptions& o, const std::string& v) { o.sweep.metric = parse_metric(v); }),
        F::text(
            {.name = "backend",
             .section = "sweep",
             .key = "backend",
             .slicer = "backend",
             .group = kSweepGroup,
             .label = "Renderer",
             .help = "auto: Vulkan on a GPU, else Embree on the CPU",
             .choices = {"auto", "vulkan", "embree"}},
            OptionKind::Choice,
            [](const AnalysisOptions& o) -> OptionValue {
                return to_string(o.sweep.render.backend);
            },
            [](AnalysisOptions& o, const std::string& v) {
                o.sweep.render.backend = parse_backend(v);
            }),
        F::text(
            {.name = "device",
             .section = "sweep",
             .key = "device",
             .slicer = "device",
             .group = kSweepGroup,
             .label = "Vulkan device",
             .help = "Vulkan device name (a substring; default: GLINT_DEVICE, else the best)"},
            OptionKind::Text,
            [](const AnalysisOptions& o) { return F::text_or_unset(o.sweep.render.device); },
            [](AnalysisOptions& o, const std::string& v) { o.sweep.render.device = v; },
            [](AnalysisOptions& o) { o.sweep.render.device.clear(); }),
        F::text(
            {.name = "accumulate",
             .section = "sweep",
             .key = "accumulate",
             .slicer = "accumulate",
             .group = kSweepGroup,
             .label = "Compare on",
             .help = "Compare and back-project on the GPU or the CPU: auto (GPU with Vulkan, "
                     "unless per-view EXRs are written)",
             .choices = {"auto", "gpu", "host"}},
            OptionKind::Choice,
            [](const AnalysisOptions& o) -> OptionValue { return to_string(o.sweep.accumulate); },
            [](AnalysisOptions& o, const std::string& v) {
                o.sweep.accumulate = parse_accumulation(v);
            }),
        F::number(
            {.name = "max_incidence",
             .section = "sweep",
             .key = "max_incidence",
             .slicer = "maxIncidence",
             .group = kSweepGroup,
             .unit = "deg",
             .min = 0,
             .max = 90,
             .min_exclusive = true,
             .max_exclusive = true,
             .label = "Max incidence",
             .help = "Coverage rule: a pixel seen more obliquely than this is not compared"},
            [](auto& o) -> auto& { return o.sweep.max_incidence_deg; }),
        F::number(
            {.name = "min_coverage",
             .section = "sweep",
             .key = "min_coverage",
             .slicer = "minCoverage",
             .group = kSweepGroup,
             .min = 0,
             .max = 1,
             .min_exclusive = true,
             .label = "Min pixel coverage",
             .help = "A pixel is compared when this share of its sub-samples hit both surfaces"},
            [](auto& o) -> auto& { return o.sweep.compare.min_coverage; }),
    };
}

std::vector<Field> decision_fields() {
    return {
        F::text(
            {.name = "rule",
             .section = "decision",
             .key = "rule",
             .slicer = "rule",
             .group = kDecisionGroup,
             .label = "Rule",
             .help = "fused: normal-field and shape evidence; normal: the paper's angle-only rule",
             .choices = {"fused", "normal"}},
            OptionKind::Choice,
            [](const AnalysisOptions& o) -> OptionValue { return to_string(o.decision.rule); },
            [](AnalysisOptions& o, const std::string& v) {
                o.decision.rule = parse_decision_rule(v);
            }),
        F::optional_number(
            {.name = "threshold_deg",
             .section = "threshold",
             .key = "deg",
             .slicer = "thresholdDeg",
             .group = kDecisionGroup,
             .unit = "metric unit",
             .min = 0,
             .min_exclusive = true,
             .label = "Normal threshold",
             .help = "Normal evidence threshold in the metric's unit (default: the "
                     "run's noise floor)"},
            [](auto& o) -> auto& { return o.decision.threshold; }),
        F::number(
            {.name = "noise_k",
             .section = "threshold",
             .key = "noise_k",
             .slicer = "noiseK",
             .group = kDecisionGroup,
             .min = 0,
             .min_exclusive = true,
             .label = "Normal floor k",
             .help = "Normal floor: median + k x 1.4826 x MAD"},
            [](auto& o) -> auto& { return o.decision.noise_k; }),
        F::number(
            {.name = "min_threshold_deg",
             .section = "threshold",
             .key = "min_deg",
             .slicer = "minThresholdDeg",
             .group = kDecisionGroup,
             .unit = "metric unit",
             .min = 0,
             .label = "Normal floor minimum",
             .help = "The normal floor is never below this"},
            [](auto& o) -> auto& { return o.decision.min_threshold; }),
        F::integer(
            {.name = "min_region_vertices",
             .section = "threshold",
             .key = "min_region_vertices",
             .slicer = "minRegionVertices",
             .group = kDecisionGroup,
             .min = 1,
             .max = 1e9,
             .label = "Smallest region",
             .help = "Connected groups of fewer vertices are dropped"},
            [](auto& o) -> auto& { return o.decision.min_region_vertices; }),
        F::number(
            {.name = "max_plausible_deg",
             .section = "decision",
             .key = "max_plausible_deg",
             .slicer = "maxPlausibleDeg",
             .group = kDecisionGroup,
             .unit = "deg",
             .min = 0,
             .min_exclusive = true,
             .label = "Plausible normal floor",
             .help = "A normal floor estimated above this is implausible: capped and reported"},
            [](auto& o) -> auto& { return o.decision.max_plausible_threshold_deg; }),
        F::optional_number(
            {.name = "resolution",
             .section = "decision",
             .key = "resolution",
             .slicer = "resolution",
             .group = kDecisionGroup,
             .unit = "mesh units",
             .min = 0,
             .min_exclusive = true,
             .label = "Scan resolution",
             .help = "For meshes read from files: the voxel edge of the scans they were segmented "
                     "from; where two sheets of surface lie closer than it, the pair is not "
                     "compared (below resolution). Surfaces extracted from volumes use their own "
                     "grid"},
            [](auto& o) -> auto& { return o.decision.resolution; }),
        F::optional_number(
            {.name = "shape_threshold",
             .section = "decision",
             .key = "shape_threshold",
             .slicer = "shapeThreshold",
             .group = kDecisionGroup,
             .unit = "mesh units",
             .min = 0,
             .min_exclusive = true,
             .label = "Shape threshold",
             .help = "Shape evidence threshold (default: the run's floor)"},
            [](auto& o) -> auto& { return o.decision.shape_threshold; }),
        F::number(
            {.name = "shape_k",
             .section = "decision",
             .key = "shape_k",
             .slicer = "shapeK",
             .group = kDecisionGroup,
             .min = 0,
             .min_exclusive = true,
             .label = "Shape floor k",
             .help = "Shape floor: median + k x 1.4826 x MAD of the shape excess"},
            [](auto& o) -> auto& { return o.decision.shape_k; }),
        F::number(
            {.name = "shape_low_k",
             .section = "decision",
             .key = "shape_low_k",
             .slicer = "shapeLowK",
             .group = kDecisionGroup,
             .min = 0,
             .min_exclusive = true,
             .label = "Shape growth k",
             .help = "Lower (hysteresis) shape floor's k, at most shape_k"},
            [](auto& o) -> auto& { return o.decision.shape_low_k; }),
        F::number(
            {.name = "min_shape_fraction",
             .section = "decision",
             .key = "min_shape_fraction",
             .slicer = "minShapeFraction",
             .group = kDecisionGroup,
             .min = 0,
             .label = "Shape floor minimum",
             .help = "The shape floor is never below this share of the bounding diagonal"},
            [](auto& o) -> auto& { return o.decision.min_shape_fraction; }),
        F::number(
            {.name = "max_plausible_shape_fraction",
             .section = "decision",
             .key = "max_plausible_shape_fraction",
             .slicer = "maxPlausibleShapeFraction",
             .group = kDecisionGroup,
             .min = 0,
             .min_exclusive = true,
             .label = "Plausible shape floor",
             .help = "A shape floor above this share of the bounding diagonal is implausible"},
            [](auto& o) -> auto& { return o.decision.max_plausible_shape_fraction; }),
        F::number(
            {.name = "grow_fraction",
             .section = "decision",
             .key = "grow_fraction",
             .slicer = "growFraction",
             .group = kDecisionGroup,
             .min = 0,
             .max = 1,
             .min_exclusive = true,
             .max_exclusive = true,
             .label = "Region growth",
             .help = "A region grows through vertices whose shape change is at least this share "
                     "of its peak"},
            [](auto& o) -> auto& { return o.decision.grow_fraction; }),
        F::flag(
            {.name = "fill_holes",
             .section = "decision",
             .key = "fill_holes",
             .slicer = "fillHoles",
             .group = kDecisionGroup,
             .label = "Fill holes",
             .help = "Fill holes inside a region (--no-fill-holes keeps them)"},
            [](auto& o) -> auto& { return o.decision.fill_holes; }),
    };
}

}  // namespace

const std::vector<OptionField<AnalysisOptions>>& analysis_option_table() {
    static const std::vector<Field> table = [] {
        std::vector<Field> all;
        for (auto part :
             {unit_fields(), fit_fields(), plan_fields(), render_fields(), decision_fields()})
            for (auto& f : part) all.push_back(std::move(f));
        return all;
    }();
    return table;
}

}  // namespace glint
