#include "scanner/sweep.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/fault_injection.h"
#include "mesh/front_end.h"
#include "mesh/stopwatch.h"
#include "scanner/backproject.h"
#include "scanner/gpu_sweep.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <thread>

namespace glint {

namespace {

using Clock = std::chrono::steady_clock;

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

namespace {

// One view's comparison and back-projection as its bands of rows arrive (on the workers),
// then its fold into the atlas (on the calling thread, in view order). Bands are known by
// their first row; a worker writes only its band's rows of the maps and its band's entries.
class ViewStream {
  public:
    ViewStream(const Mesh& reference, const SweepPlan& plan, const SweepOptions& options,
               int threads)
        : reference_(reference),
          plan_(plan),
          options_(options),
          threads_(threads),
          backproject_{
              .min_cos_incidence = std::cos(options.max_incidence_deg * std::numbers::pi / 180.0),
              .min_coverage = options.compare.min_coverage,
              .missing_value = describe(options.metric).missing_value,
              .framed_radius = plan.radius} {
        for (double f : plan.footprints) atlases_.emplace_back(reference, f);
        prepare(0);
    }

    // A band of both frames of the view prepared (any worker; bands concurrently).
    void rows(const FrameRows& ref, const FrameRows& exa) {
        const auto t0 = Clock::now();
        const std::size_t first =
            static_cast<std::size_t>(ref.y0) * static_cast<std::size_t>(ref.width);
        const std::size_t n = ref.pixel_count();
        DeviationMap& d = maps_.deviation;
        const FrameView rv = frame_view(ref), ev = frame_view(exa);
        const std::span<float> angle = std::span(d.angle_deg).subspan(first, n);
        compare_pixels(rv, ev, options_.compare, angle, std::span(d.signed_depth).subspan(first, n),
                       std::span(d.silhouette).subspan(first, n));
        describe(options_.metric).compute(rv, ev, angle, std::span(d.value).subspan(first, n));
        record_reference_rows(ref, options_.compare.min_coverage, maps_);
        const auto band = static_cast<std::size_t>(ref.y0);
        samples_[band].clear();
        covered_[band] =
            scatter_rows(reference_, view_->view, ref, maps_, backproject_, samples_[band]);
        is_band_[band] = 1;
        worker_seconds_.fetch_add(seconds_since(t0), std::memory_order_relaxed);
    }

    // View i is whole: its summary, the fold into its zoom's atlas, the observer; then the
    // next view is prepared.
    ViewSummary done(std::size_t i, const ViewObserver& observer) {
        GLINT_ASSERT(view_ == &plan_.views[i], "sweep: views handed on out of order");
        const PlannedView& pv = *view_;
        DeviationMap& dev = maps_.deviation;
        summarise(dev);
        std::vector<const std::vector<AtlasSample>*> bands;
        std::size_t covered = 0;
        for (std::size_t y = 0; y < is_band_.size(); ++y)
            if (is_band_[y]) {
                bands.push_back(&samples_[y]);
                covered += covered_[y];
            }
        fold_view(reference_, pv.view, bands, maps_, backproject_,
                  atlases_[static_cast<std::size_t>(pv.view.zoom_index)], scratch_, threads_);
        if (observer) observer(pv, dev);
        ViewSummary s;
        s.index = pv.view.index;
        s.reference_pixels = covered;
        s.compared = dev.compared;
        s.reference_only = dev.reference_only;
        s.examined_only = dev.examined_only;
        s.max_angle_deg = dev.max_angle_deg;
        s.mean_angle_deg = dev.mean_angle_deg;
        if (i + 1 < plan_.views.size()) prepare(i + 1);
        return s;
    }

    /// The accumulators, handed over (the stream is done with them).
    [[nodiscard]] std::vector<AtlasAccumulator> take_atlases() { return std::move(atlases_); }
    /// Seconds the workers spent comparing and scattering, summed over them.
    [[nodiscard]] double worker_seconds() const { return worker_seconds_.load(); }

  private:
    // Maps and band entries sized for view i (storage kept across views).
    void prepare(std::size_t i) {
        view_ = &plan_.views[i];
        const Camera& c = view_->view.camera;
        maps_.resize(c.width, c.height);
        const auto rows = static_cast<std::size_t>(c.height);
        samples_.resize(rows);
        covered_.assign(rows, 0);
        is_band_.assign(rows, 0);
    }

    const Mesh& reference_;
    const SweepPlan& plan_;
    const SweepOptions& options_;
    int threads_;
    BackprojectOptions backproject_;
    std::vector<AtlasAccumulator> atlases_;
    BackprojectScratch scratch_;
    const PlannedView* view_ = nullptr;  // the view whose bands arrive
    ViewMaps maps_;
    std::vector<std::vector<AtlasSample>> samples_;  // per band, by its first row
    std::vector<std::size_t> covered_;               // per band: covered reference pixels
    std::vector<std::uint8_t> is_band_;              // 1 at the first row of each band seen
    std::atomic<double> worker_seconds_{0.0};
};

}  // namespace

// A reference drawn on fewer pixels than this in every view is a speck in its frame.
constexpr std::size_t kFewPixels = 16;

void require_overlap(const std::vector<ViewSummary>& views) {
    std::size_t compared = 0, examined = 0, largest = 0;
    for (const auto& v : views) {
        compared += v.compared;
        examined += v.examined_only;
        largest = std::max(largest, v.reference_pixels);
    }
    if (compared > 0) return;
    const std::string n = std::to_string(views.size());
    // note: which of the surfaces the views saw tells the causes apart (issue 52: parts far
    // apart, coordinates too large and a fit far off all read "check the fit").
    if (largest < kFewPixels)
        throw InputError("sweep: the reference covers at most " + std::to_string(largest) +
                         " pixels of any of the " + n +
                         " views: it is too small in the frame, whose size its whole extent sets "
                         "(parts far apart from each other); expected a surface that fills the "
                         "views (analyse one part, or raise " +
                         spell_option("size", "PIXELS") + ")");
    if (examined == 0)
        throw InputError("sweep: the fitted examined surface appears in none of the " + n +
                         " views, the reference in up to " + std::to_string(largest) +
                         " pixels of each; expected the examined surface on the reference: check "
                         "the fit (" +
                         spell_option("fit", "FILE") + ", " + spell_flag("register") +
                         ", landmarks)");
    throw InputError(
        "sweep: the reference and the fitted examined surface do not overlap in any of the " + n +
        " views (no pixel shows both); check the fit (" + spell_option("fit", "FILE") + ", " +
        spell_flag("register") + ", landmarks)");
}

SweepResult run_sweep(const Mesh& reference, const Mesh& examined, const SweepPlan& plan,
                      const SweepOptions& options, const ViewObserver& observer,
                      const SweepSurfaces& surfaces) {
    const auto t_start = Clock::now();
    options.validate();
    if (plan.views.empty()) throw InputError("sweep plan has no views");
    if (!reference.has_normals())
        throw InputError("sweep: the reference mesh has no vertex normals");
    SweepResult result;
    result.plan = plan;
    result.options = options;

    // One device for the process (render/context.h), both meshes on it, read in place (they
    // outlive the renderers).
    const auto context = shared_render_context(options.render.context_options());
    FrameOptions frames = options.render.frame_options();
    frames.share_mesh = true;
    // Each CPU renderer casts into the surface's BVH when the run built one already.
    FrameOptions ref_frames = frames, exa_frames = frames;
    ref_frames.surface_index = surfaces.reference;
    exa_frames.surface_index = surfaces.examined;
    std::optional<Renderer> ref_renderer(std::in_place, context, reference, ref_frames);
    std::optional<Renderer> exa_renderer(std::in_place, context, examined, exa_frames);
    result.renderer = ref_renderer->info();
    // Compare and back-project on the GPU when the options and the device allow it
    // (scanner/gpu_sweep.h); the streamed path below is the reference it is tested against.
    if (run_sweep_on_gpu(reference, *ref_renderer, *exa_renderer, plan, options, observer,
                         result)) {
        result.total_seconds = seconds_since(t_start);
        return result;
    }

    const int threads = std::max(1, options.render.threads > 0
                                        ? options.render.threads
                                        : static_cast<int>(std::thread::hardware_concurrency()));
    ViewStream stream(reference, plan, options, threads);
    std::vector<View> views;
    views.reserve(plan.views.size());
    for (const auto& p : plan.views) views.push_back(p.view);

    const auto t_views = Clock::now();
    double fold_seconds = 0.0;
    render_view_pair_rows(
        *ref_renderer, *exa_renderer, views,
        [&](std::size_t, const FrameRows& ref, const FrameRows& exa) { stream.rows(ref, exa); },
        [&](std::size_t i) {
            fault_point("view");
            throw_if_cancelled();
            const auto t = Clock::now();
            result.views.push_back(stream.done(i, observer));
            fold_seconds += seconds_since(t);
        });
    const double views_seconds = seconds_since(t_views);
    exa_renderer.reset();  // the scenes go before the atlases are finished (peak memory)
    ref_renderer.reset();
    result.compare_seconds =
        std::min(views_seconds, fold_seconds + stream.worker_seconds() / threads);
    result.render_seconds = views_seconds - result.compare_seconds;
    require_overlap(result.views);
    for (auto& a : stream.take_atlases()) {
        SweepZoom z;
        z.atlas = std::move(a).finish();
        z.coverage = coverage_of(reference, z.atlas, plan.options.roi);
        result.zooms.push_back(std::move(z));
    }
    result.total_seconds = seconds_since(t_start);
    return result;
}

}  // namespace glint
