#include "report/pictures.h"

#include "mesh/atomic_file.h"
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "render/renderer.h"
#include "report/detail/atlas_overview.h"
#include "report/detail/canvas.h"
#include "report/detail/footer.h"
#include "report/detail/labels.h"
#include "report/detail/legend.h"
#include "report/detail/picture_batches.h"
#include "report/detail/scale_bar.h"
#include "report/detail/surface_paint.h"
#include "scanner/metric.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

namespace glint {

namespace fs = std::filesystem;
using OIIO::ImageBuf;
namespace IBA = OIIO::ImageBufAlgo;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr int kViewMin = 384;  // px: per-view pictures are at least this large …
constexpr int kViewMax = 512;  // … and at most this (rendered at that size, never resized)
constexpr int kRowLabel = 58;  // px: mosaic row headings
constexpr int kColLabel = 18;  // px: mosaic column headings
constexpr int kGap = 2;        // px between mosaic tiles
// One ray per pixel: pictures are drawn at the size they are shown (384-512 px per view), where
// a 2×2 footprint only smooths the silhouette's steps. note: with 2×2 the 60 per-view pictures
// of a default sweep cost 35 M rays, more than the sweep's own two meshes (2 × 16 M); at 1×1
// a whole 200k-triangle inspection took 0.4 s less on 2 cores (2.88 instead of 3.28 s, medians
// of 5 alternating runs; issue 13), the silhouettes a little more stepped.
constexpr int kPictureSupersample = 1;

// 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10^k: the smallest at or above x (x > 0).
double nice_ceiling(double x) {
    const double e = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
        if (m * e >= x * (1 - 1e-9)) return m * e;
    return 10.0 * e;
}

std::string unit_or_units(const AnalysisResult& r) { return r.unit.empty() ? "units" : r.unit; }

// Everything a picture of zoom z shows: the fields and the legend.
struct ZoomContent {
    detail::SurfaceFields fields;
    detail::LegendContent legend;
};

detail::LegendContent legend_for(const AnalysisResult& result, std::size_t z,
                                 const ShapeScale& scale) {
    const auto& d = result.decisions[z];
    const MetricDescriptor& m = describe(result.sweep.options.metric);
    const std::string u = unit_or_units(result);
    detail::LegendContent c{.limit = scale.limit,
                            .limit_source = scale.source,
                            .shape_floor = d.rule == DecisionRule::Fused ? d.shape.value : 0.0,
                            .unit = u,
                            .roi = result.sweep.plan.options.roi.has_value()};
    char b[160];
    std::snprintf(b, sizeof b, "normal floor %.3g%s (%s, %s rule)", d.normal.value,
                  detail::picture_unit_suffix(d.scale.radius > 0 ? "deg" : m.unit).c_str(),
                  to_string(d.normal.source).c_str(), to_string(d.rule).c_str());
    c.lines.emplace_back(b);
    std::snprintf(b, sizeof b, "zoom %zu: %s %s/px, coverage %.0f %%, compared %.0f %%", z,
                  detail::format_number(result.sweep.plan.footprints[z]).c_str(), u.c_str(),
                  100.0 * result.sweep.zooms[z].coverage.fraction, 100.0 * d.comparison.fraction);
    c.lines.emplace_back(b);
    for (const auto& r : d.regions.regions) c.regions.push_back(detail::region_legend_line(r, u));
    return c;
}

// The same camera rendering `size` pixels across (orthographic: same world extent; perspective:
// same field of view).
View resized(const View& v, int size) {
    View r = v;
    const double s = static_cast<double>(size) / std::max(v.camera.width, v.camera.height);
    r.camera.width = std::max(1, static_cast<int>(std::lround(v.camera.width * s)));
    r.camera.height = std::max(1, static_cast<int>(std::lround(v.camera.height * s)));
    // (the same extent over more or fewer pixels: the scale bar reads the footprint)
    r.footprint = v.footprint / s;
    return r;
}

class PictureWriter {
  public:
    PictureWriter(const Mesh& reference, const AnalysisResult& result, const ExportOptions& options,
                  Orientation orientation, PictureCaption caption)
        : reference_(reference),
          result_(result),
          caption_(std::move(caption)),
          options_(options),
          orientation_(std::move(orientation)),
          scale_(shape_scale(result)),
          threads_(result.sweep.options.render.threads),
          renderer_(shared_render_context(
                        ContextOptions{.backend = Backend::Embree, .threads = threads_}),
                    reference,
                    FrameOptions{.supersample = kPictureSupersample,
                                 .share_mesh = true,
                                 .barycentrics = true,
                                 .surface_index = result.reference_index}) {
        const std::size_t n = reference.vertex_count();
        distance_ = result.distance.size() == n ? result.distance : std::vector<float>(n, kNaN);
        masks_.resize(result.sweep.zooms.size());
        for (std::size_t z = 0; z < result.sweep.zooms.size(); ++z) {
            const auto& seen = result.sweep.zooms[z].coverage.seen;
            const auto& comparison = result.decisions[z].comparison;
            auto& shown = masks_[z];
            shown.resize(n);
            for (std::size_t v = 0; v < n; ++v)
                shown[v] = !seen[v] ? 0 : comparison.compared(v) ? 1 : 2;
            const auto& region = result.decisions[z].regions.region_of_vertex;
            zooms_.push_back({{distance_, region, shown}, legend_for(result, z, scale_)});
        }
        // The regions' best views, largest regions first (regions are sorted by area).
        for (std::size_t k = 0; best_.size() < kMaxBestViews; ++k) {
            bool any = false;
            for (const auto& d : result.decisions)
                if (k < d.regions.regions.size()) {
                    any = true;
                    const int v = d.regions.regions[k].best_view;
                    if (v >= 0 && static_cast<std::size_t>(v) < result.sweep.plan.views.size() &&
                        best_.size() < kMaxBestViews)
                        best_.insert(v);
                }
            if (!any) break;
        }
    }

    void write_views(const OutputFolder& folder, PictureOutput& out,
                     const AnalysisObserver& observer);
    std::string mosaic(std::size_t z);
    std::string atlas_overview() {
        const std::string name =
            caption_.reference_name.empty() ? "the reference" : caption_.reference_name;
        const detail::FooterInput footer{
            .reference_name = caption_.reference_name,
            .examined_name = caption_.examined_name,
            .date = caption_.date.empty() ? detail::utc_date_now() : caption_.date};
        return detail::atlas_overview_png(renderer_,
                                          {.mesh = &reference_,
                                           .fields = &zooms_[0].fields,
                                           .legend = &zooms_[0].legend,
                                           .limit = scale_.limit,
                                           .regions = &result_.decisions[0].regions.regions,
                                           .plan = &result_.sweep.plan,
                                           .coverage = result_.sweep.zooms[0].coverage.fraction,
                                           .name = name,
                                           .unit = unit_or_units(result_),
                                           .orientation = &orientation_,
                                           .footer = detail::footer_lines(result_, footer)});
    }

  private:
    ImageBuf view_picture(const PlannedView& pv, const View& shown, const Frame& frame,
                          const ImageBuf& blank);

    const Mesh& reference_;
    const AnalysisResult& result_;
    PictureCaption caption_;
    const ExportOptions& options_;
    Orientation orientation_;
    ShapeScale scale_;
    int threads_ = 0;  ///< workers (RenderOptions::threads: 0 = the machine's)
    Renderer renderer_;
    std::vector<float> distance_;
    std::vector<ZoomContent> zooms_;
    // Per zoom: 0 unseen, 1 compared, 2 seen but not compared (the pictures' fields point here).
    std::vector<std::vector<std::uint8_t>> masks_ = {};
    std::set<int> best_;
};

// `blank`: the zoom's framed sheet at the frame's size with no title (its legend drawn once).
ImageBuf PictureWriter::view_picture(const PlannedView& pv, const View& shown, const Frame& frame,
                                     const ImageBuf& blank) {
    const View& v = pv.view;
    const auto z = static_cast<std::size_t>(v.zoom_index);
    const auto painted =
        detail::paint_surface(reference_, frame, shown, zooms_[z].fields, {.limit = scale_.limit});
    // In a patient space the view is also named from where it looks ("from anterior-left").
    const std::string from =
        orientation_.space == PatientSpace::Unknown
            ? std::string()
            : " from " + orientation_.name(shown.camera.world_from_camera.linear().col(2));
    char title[240];
    std::snprintf(title, sizeof title, "view %d%s: azimuth %s, elevation %s, zoom %d (%s %s/px)",
                  v.index, from.c_str(), detail::format_degrees(v.azimuth_deg).c_str(),
                  detail::format_degrees(v.elevation_deg, true).c_str(), v.zoom_index,
                  detail::format_number(v.footprint).c_str(), unit_or_units(result_).c_str());
    ImageBuf sheet = blank;
    detail::draw_title(sheet, detail::with_minus_sign(title));
    IBA::paste(sheet, 0, detail::kTitleHeight, 0, 0, painted.image);
    const std::string unit = unit_or_units(result_);
    detail::draw_region_numbers(sheet, 0, detail::kTitleHeight, frame.width, frame.height,
                                painted.anchors, 14, 30, {detail::view_scale_bar_box(shown, unit)});
    detail::draw_view_scale_bar(sheet, 0, detail::kTitleHeight, shown, unit);
    return sheet;
}

void PictureWriter::write_views(const OutputFolder& folder, PictureOutput& out,
                                const AnalysisObserver& observer) {
    const auto& plan = result_.sweep.plan;
    std::vector<int> wanted;
    for (const auto& pv : plan.views)
        if (options_.write_views || best_.count(pv.view.index)) wanted.push_back(pv.view.index);
    std::vector<View> shown;
    std::map<std::size_t, ImageBuf> blank;  // per zoom: every view of a zoom has one size
    for (int i : wanted) {
        const auto& pv = plan.views[static_cast<std::size_t>(i)];
        const auto z = static_cast<std::size_t>(pv.view.zoom_index);
        shown.push_back(
            upright(resized(pv.view, std::clamp(plan.sizes[z], kViewMin, kViewMax)), orientation_));
        if (!blank.count(z))
            blank.emplace(
                z, detail::framed_sheet(shown.back().camera.width, shown.back().camera.height, "",
                                        zooms_[z].legend));
    }
    // Painted and encoded on every worker; the best views' PNGs kept for the report page.
    std::vector<std::string> kept(detail::batch_size(threads_));
    detail::render_in_batches(
        renderer_, shown, threads_,
        [&](std::size_t slot, std::size_t k, const Frame& frame) {
            const auto& pv = plan.views[static_cast<std::size_t>(wanted[k])];
            const ImageBuf& sheet = blank.at(static_cast<std::size_t>(pv.view.zoom_index));
            std::string png = detail::encode_png(view_picture(pv, shown[k], frame, sheet));
            if (options_.write_views)
                write_file_atomically(
                    folder.file(fs::path("views") / (view_file_stem(pv.view) + ".png")), png);
            kept[slot] = best_.count(pv.view.index) ? std::move(png) : std::string();
        },
        [&](std::size_t slot, std::size_t k) {
            if (!kept[slot].empty()) out.best_views[wanted[k]] = std::move(kept[slot]);
            if (observer.items) observer.items(k + 1, wanted.size());
        });
}

std::string PictureWriter::mosaic(std::size_t z) {
    const auto& plan = result_.sweep.plan;
    const bool rotary = plan.options.kind == SweepPlanOptions::Kind::Rotary;
    const int t = options_.mosaic_tile;
    std::vector<const PlannedView*> members;
    std::vector<View> shown;
    for (const auto& pv : plan.views)
        if (static_cast<std::size_t>(pv.view.zoom_index) == z) {
            members.push_back(&pv);
            shown.push_back(upright(resized(pv.view, t), orientation_));
        }
    const int grid_w = kRowLabel + plan.columns * (t + kGap);
    const int grid_h = kColLabel + plan.rows * (t + kGap);
    char title[220];
    std::snprintf(title, sizeof title,
                  "signed shape change, zoom %zu (%s %s/px): %zu views, %zu region(s)", z,
                  detail::format_number(plan.footprints[z]).c_str(), unit_or_units(result_).c_str(),
                  members.size(), result_.decisions[z].regions.regions.size());
    ImageBuf sheet = detail::framed_sheet(grid_w, grid_h, title, zooms_[z].legend);
    std::vector<detail::PaintedSurface> painted(detail::batch_size(threads_));
    detail::render_in_batches(
        renderer_, shown, threads_,
        [&](std::size_t slot, std::size_t k, const Frame& frame) {
            painted[slot] = detail::paint_surface(
                reference_, frame, shown[k], zooms_[z].fields,
                {.limit = scale_.limit, .outline_width = 1, .hatch_period = 5});
        },
        [&](std::size_t slot, std::size_t k) {
            const PlannedView& pv = *members[k];
            const auto& tile = painted[slot].image.spec();
            const int col = rotary ? pv.step : pv.step % plan.columns;
            const int row = rotary ? pv.ring : pv.step / plan.columns;
            const int x = kRowLabel + col * (t + kGap) + (t - tile.width) / 2;
            const int y =
                detail::kTitleHeight + kColLabel + row * (t + kGap) + (t - tile.height) / 2;
            IBA::paste(sheet, x, y, 0, 0, painted[slot].image);
            detail::draw_region_numbers(sheet, x, y, tile.width, tile.height, painted[slot].anchors,
                                        10, 4);
            if (!rotary) {
                char label[48];
                std::snprintf(label, sizeof label, "%s/%s",
                              detail::format_degrees(pv.view.azimuth_deg).c_str(),
                              detail::format_degrees(pv.view.elevation_deg, true).c_str());
                detail::draw_text(sheet, x + 3, y + 11, label, 10, detail::kText);
            }
        });
    if (rotary) {
        for (int c = 0; c < plan.columns; ++c) {
            char b[32];
            std::snprintf(b, sizeof b, "az %s",
                          detail::format_degrees(c * plan.options.azimuth_step_deg).c_str());
            detail::draw_text(sheet, kRowLabel + c * (t + kGap) + t / 2, detail::kTitleHeight + 13,
                              b, 11, detail::kText, IBA::TextAlignX::Center);
        }
        for (std::size_t r = 0; r < plan.options.elevations_deg.size(); ++r) {
            char b[32];
            std::snprintf(b, sizeof b, "el %s",
                          detail::format_degrees(plan.options.elevations_deg[r], true).c_str());
            detail::draw_text(
                sheet, 4,
                detail::kTitleHeight + kColLabel + static_cast<int>(r) * (t + kGap) + t / 2 + 4, b,
                11);
        }
    }
    return detail::encode_png(sheet);
}

}  // namespace

ShapeScale shape_scale(const AnalysisResult& result) {
    ShapeScale s;
    if (!result.decisions.empty() && result.decisions[0].rule == DecisionRule::Fused)
        s.floor = result.decisions[0].shape.value;
    // note: the median, not the largest: one large change (a resection, a misfit part) would
    // leave every other region pale; changes beyond the range are drawn at full colour.
    std::vector<double> peaks;
    if (!result.decisions.empty())
        for (const auto& r : result.decisions[0].regions.regions)
            if (r.kind != RegionKind::MissingSurface && std::isfinite(r.peak_depth))
                peaks.push_back(std::abs(r.peak_depth));
    if (!peaks.empty()) {
        std::sort(peaks.begin(), peaks.end());
        const std::size_t m = peaks.size() / 2;
        s.limit = peaks.size() % 2 ? peaks[m] : 0.5 * (peaks[m - 1] + peaks[m]);
        s.source = peaks.size() == 1 ? "region peak" : "median region peak";
    } else {
        std::vector<float> mag;
        const auto* seen =
            result.sweep.zooms.empty() ? nullptr : &result.sweep.zooms[0].coverage.seen;
        const Comparison* compared =
            result.decisions.empty() ? nullptr : &result.decisions[0].comparison;
        for (std::size_t v = 0; v < result.distance.size(); ++v)
            if (std::isfinite(result.distance[v]) && (!seen || (*seen)[v]) &&
                (!compared || compared->compared(v)))
                mag.push_back(std::abs(result.distance[v]));
        if (!mag.empty()) {
            const auto k = static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(mag.size() - 1));
            std::nth_element(mag.begin(), mag.begin() + k, mag.end());
            s.limit = mag[static_cast<std::size_t>(k)];
            s.source = "99th percentile of |distance|";
        }
    }
    if (s.floor > 0 && s.limit < 2 * s.floor) {
        s.limit = 2 * s.floor;
        s.source = "twice the shape floor";
    }
    // note: 1e-6 of the size: a surface identical to its examined copy still gets a range.
    const double smallest = std::max(1e-6 * result.size, 1e-12);
    if (!(s.limit > smallest)) {
        s.limit = smallest;
        s.source = "no shape change";
    }
    s.limit = nice_ceiling(s.limit);
    return s;
}

std::string view_file_stem(const View& v) {
    char name[96];
    std::snprintf(name, sizeof name, "z%d_az%05.1f_el%+05.1f", v.zoom_index, v.azimuth_deg,
                  v.elevation_deg);
    return name;
}

PictureOutput write_pictures(const OutputFolder& folder, const Mesh& reference,
                             const AnalysisResult& result, const ExportOptions& options,
                             const Orientation& orientation, const PictureCaption& caption,
                             const AnalysisObserver& observer) {
    PictureOutput out;
    if (result.sweep.zooms.empty() || result.decisions.size() != result.sweep.zooms.size())
        return out;
    PictureWriter writer(reference, result, options, orientation, caption);
    writer.write_views(folder, out, observer);
    if (observer.stage) observer.stage("mosaics");
    const std::size_t zooms = result.sweep.zooms.size();
    for (std::size_t z = 0; z < zooms; ++z) {
        out.mosaics.push_back(writer.mosaic(z));
        write_file_atomically(folder.file("mosaic_z" + std::to_string(z) + ".png"),
                              out.mosaics.back());
        if (observer.items) observer.items(z + 1, zooms);
    }
    if (observer.stage) observer.stage("atlas.png");
    out.atlas = writer.atlas_overview();
    write_file_atomically(folder.file("atlas.png"), out.atlas);
    return out;
}

}  // namespace glint
