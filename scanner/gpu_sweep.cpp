#include "scanner/gpu_sweep.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/fault_injection.h"
#include "mesh/stopwatch.h"
#include "render/gpu_atlas.h"
#include "scanner/coverage.h"

#include <chrono>
#include <cmath>
#include <numbers>

namespace glint {

Accumulation parse_accumulation(const std::string& text) {
    if (text == "auto") return Accumulation::Auto;
    if (text == "gpu") return Accumulation::Gpu;
    if (text == "host") return Accumulation::Host;
    throw InputError("accumulate \"" + text + "\": expected auto, gpu or host");
}

std::string to_string(Accumulation accumulation) {
    switch (accumulation) {
        case Accumulation::Auto: return "auto";
        case Accumulation::Gpu: return "gpu";
        case Accumulation::Host: return "host";
    }
    return "?";
}

namespace {

using Clock = std::chrono::steady_clock;

GpuAtlasOptions atlas_options(const SweepPlan& plan, const SweepOptions& options) {
    return GpuAtlasOptions{
        .metric = options.metric,
        .missing_value = describe(options.metric).missing_value,
        .min_coverage = options.compare.min_coverage,
        .min_cos_incidence = std::cos(options.max_incidence_deg * std::numbers::pi / 180.0),
        .framed_radius = plan.radius,
        .zoom_count = static_cast<int>(plan.footprints.size())};
}

}  // namespace

bool run_sweep_on_gpu(const Mesh& reference, Renderer& reference_renderer,
                      Renderer& examined_renderer, const SweepPlan& plan,
                      const SweepOptions& options, const ViewObserver& observer,
                      SweepResult& result) {
    if (options.accumulate == Accumulation::Host) return false;
    const GpuAtlasOptions atlas_opts = atlas_options(plan, options);
    std::string why;
    if (!GpuAtlas::supported(reference_renderer, examined_renderer, atlas_opts, &why)) {
        if (options.accumulate == Accumulation::Gpu)
            throw DeviceError("sweep: accumulate = gpu, but " + why);
        result.accumulation_note = "compare and back-projection on the CPU: " + why;
        return false;
    }
    GpuAtlas atlas(reference_renderer, examined_renderer, atlas_opts);
    std::vector<View> views;
    views.reserve(plan.views.size());
    for (const auto& p : plan.views) views.push_back(p.view);

    const DeviationMap no_deviation;
    const auto t_run = Clock::now();
    atlas.run(views, [&](std::size_t i, const ViewNumbers& g) {
        fault_point("view");
        throw_if_cancelled();
        const PlannedView& pv = plan.views[i];
        ViewSummary summary;
        static_cast<ViewNumbers&>(summary) = g;
        summary.index = pv.view.index;
        result.views.push_back(summary);
        if (observer) observer(pv, no_deviation);
    });
    result.render_seconds = seconds_since(t_run);
    require_overlap(result.views);
    const auto t_read = Clock::now();
    std::vector<AtlasTotals> totals = atlas.read_totals();
    GLINT_ASSERT(totals.size() == plan.footprints.size(), "one atlas per zoom");
    GLINT_ASSERT(totals.empty() || totals[0].size() == reference.vertex_count(),
                 "atlas does not match the mesh");
    for (std::size_t z = 0; z < totals.size(); ++z) {
        SweepZoom zoom;
        zoom.atlas = finish_atlas(std::move(totals[z]), plan.footprints[z]);
        zoom.coverage = coverage_of(reference, zoom.atlas, plan.options.roi);
        result.zooms.push_back(std::move(zoom));
    }
    result.compare_seconds = seconds_since(t_read);
    result.on_gpu = true;
    return true;
}

}  // namespace glint
