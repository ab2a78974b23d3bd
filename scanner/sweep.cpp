#include "scanner/sweep.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "scanner/backproject.h"
#include "scanner/gpu_sweep.h"

#include <chrono>
#include <cmath>
#include <numbers>

namespace glint {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

ViewSummary summarise(const PlannedView& pv, const DeviationMap& dev, std::size_t reference_pixels) {
    ViewSummary s;
    s.index = pv.view.index;
    s.reference_pixels = reference_pixels;
    s.compared = dev.compared;
    s.reference_only = dev.reference_only;
    s.examined_only = dev.examined_only;
    s.max_angle_deg = dev.max_angle_deg;
    s.mean_angle_deg = dev.mean_angle_deg;
    return s;
}

}  // namespace

void SweepOptions::validate() const {
    try {
        plan.validate();
        render.validate();
    } catch (const OptionError& e) {
        throw e.prefixed("sweep");
    }
    if (!(max_incidence_deg > 0 && max_incidence_deg < 90))
        throw OptionError("sweep.max_incidence", max_incidence_deg, "must be in (0, 90) degrees");
    if (!(compare.min_coverage > 0 && compare.min_coverage <= 1))
        throw OptionError("sweep.min_coverage", compare.min_coverage, "must be in (0, 1]");
}

SweepResult run_sweep(const Mesh& reference, const Mesh& examined, const SweepPlan& plan, const SweepOptions& options,
                      const ViewObserver& observer) {
    const auto t_start = Clock::now();
    options.validate();
    if (plan.views.empty()) throw InputError("sweep plan has no views");
    if (!reference.has_normals()) throw InputError("sweep: the reference mesh has no vertex normals");
    SweepResult result;
    result.plan = plan;
    result.options = options;

    // One device for the process (render/context.h), both meshes on it.
    const auto context = shared_render_context(options.render.context_options());
    Renderer ref_renderer(context, reference, options.render.frame_options());
    Renderer exa_renderer(context, examined, options.render.frame_options());
    result.renderer = ref_renderer.info();
    // Compare and back-project on the GPU when the options and the device allow it
    // (scanner/gpu_sweep.h); the read-back path below is the reference it is tested against.
    if (run_sweep_on_gpu(reference, ref_renderer, exa_renderer, plan, options, observer, result)) {
        result.total_seconds = seconds_since(t_start);
        return result;
    }

    std::vector<AtlasAccumulator> atlases;
    for (double f : plan.footprints) atlases.emplace_back(reference, f);
    const BackprojectOptions bp{.min_cos_incidence = std::cos(options.max_incidence_deg * std::numbers::pi / 180.0),
                                .min_coverage = options.compare.min_coverage,
                                .missing_value = describe(options.metric).missing_value,
                                .framed_radius = plan.radius};
    BackprojectScratch scratch;
    std::vector<View> views;
    views.reserve(plan.views.size());
    for (const auto& p : plan.views) views.push_back(p.view);

    auto t_view = Clock::now();
    // Both frames of a view in flight together; the next view's pair renders while this
    // one is compared.
    render_view_pairs(ref_renderer, exa_renderer, views, [&](std::size_t i, const Frame& ref_frame,
                                                             const Frame& exa_frame) {
        throw_if_cancelled();
        const PlannedView& pv = plan.views[i];
        result.render_seconds += seconds_since(t_view);
        const auto t_compare = Clock::now();
        const DeviationMap dev = compare_frames(frame_view(ref_frame), frame_view(exa_frame), options.compare, options.metric);
        auto& atlas = atlases[static_cast<std::size_t>(pv.view.zoom_index)];
        const std::size_t covered = backproject_view(reference, pv.view, ref_frame, dev, bp, atlas, scratch);
        result.views.push_back(summarise(pv, dev, covered));
        if (observer) observer(pv, ref_frame, exa_frame, dev);
        result.compare_seconds += seconds_since(t_compare);
        t_view = Clock::now();
    });
    std::size_t compared = 0;
    for (const auto& v : result.views) compared += v.compared;
    if (compared == 0)
        throw InputError("sweep: the reference and the fitted examined surface do not overlap in any of the " +
                         std::to_string(result.views.size()) +
                         " views (no pixel shows both); check the fit (--fit, --register, landmarks)");
    for (const auto& a : atlases) {
        SweepZoom z;
        z.atlas = a.finish();
        z.coverage = coverage_of(reference, z.atlas, plan.options.roi);
        result.zooms.push_back(std::move(z));
    }
    result.total_seconds = seconds_since(t_start);
    return result;
}

}  // namespace glint
