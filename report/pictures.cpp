#include "report/pictures.h"

#include "mesh/atomic_file.h"
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/mesh.h"
#include "render/renderer.h"
#include "report/detail/atlas_overview.h"
#include "report/detail/canvas.h"
#include "report/detail/footer.h"
#include "report/detail/labels.h"
#include "report/detail/legend.h"
#include "report/detail/measured_pixels.h"
#include "report/detail/picture_batches.h"
#include "report/detail/scale_bar.h"
#include "report/detail/surface_paint.h"
#include "report/detail/symmetry_plane_trace.h"
#include "report/detail/view_chart.h"
#include "scanner/metric.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

namespace glint {

namespace fs = std::filesystem;

namespace {

constexpr int kViewMin = 384;    // px: per-view pictures are at least this large …
constexpr int kViewMax = 512;    // … and at most this (rendered at that size, never resized)
constexpr int kShareSize = 128;  // px: the small pictures that count a view's share (enough pixels)
constexpr int kGap = 6;          // px between the mosaic's chart and tiles
constexpr int kTileCaption = 18;      // px: the caption under a mosaic tile
constexpr int kTilesPerRow = 4;       // mosaic tiles side by side, at least
constexpr std::size_t kMaxTiles = 8;  // views drawn whole in a mosaic, at most
// A view's depth floor is median + k·MAD of its |depth| with the shape floor's k; this one
// when the decision gave none (decision/decision.h DecisionOptions::noise_k's default).
constexpr double kDepthFloorK = 6.0;
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
    detail::LegendContent measured_legend;  ///< of pictures of a view's own measurement
};

detail::LegendContent legend_for(const AnalysisResult& result, std::size_t z,
                                 const ShapeScale& scale, bool mirror) {
    const auto& d = result.decisions[z];
    const MetricDescriptor& m = describe(result.sweep.options.metric);
    const std::string u = unit_or_units(result);
    detail::LegendContent c{.limit = scale.limit,
                            .limit_source = scale.source,
                            .shape_floor = d.rule == DecisionRule::Fused ? d.shape.value : 0.0,
                            .unit = u,
                            .roi = result.sweep.plan.options.roi.has_value(),
                            .mirror = mirror,
                            .plane_line = mirror};
    char b[160];
    const std::string normal_unit =
        detail::picture_unit_suffix(d.scale.radius > 0 ? "deg" : m.unit);
    // note: two normals differ by at most 180°; a "floor" past 90° bounds nothing a surface can
    // show, so the legend says the shape decided instead of printing "normal floor 170°" (issue 51).
    if (normal_unit == "°" && d.normal.value > 90.0)
        std::snprintf(b, sizeof b, "normals: no floor (they differ by %.3g° by nature; %s rule)",
                      d.normal.value, to_string(d.rule).c_str());
    else
        std::snprintf(b, sizeof b, "normal floor %.3g%s (%s, %s rule)", d.normal.value,
                      normal_unit.c_str(), to_string(d.normal.source).c_str(),
                      to_string(d.rule).c_str());
    c.lines.emplace_back(b);
    std::snprintf(b, sizeof b, "zoom %zu: %s %s/px, coverage %.0f %%, compared %.0f %%", z,
                  detail::format_number(result.sweep.plan.footprints[z]).c_str(), u.c_str(),
                  100.0 * result.sweep.zooms[z].coverage.fraction, 100.0 * d.comparison.fraction);
    c.lines.emplace_back(b);
    for (const auto& r : d.regions.regions)
        c.regions.push_back(detail::region_legend_line(r, u, mirror));
    return c;
}

// How far two tessellations of the surface lie apart at a pixel on most of it: the 90th
// percentile of the reference vertices' tessellation tolerance (analysis/fit.h, an upper bound
// of their distance; 0 when there is none). note: the 90th: the tolerance is largest at sharp
// edges (a jaw's teeth: 99th percentile 0.23 mm, a floor that pales its 0.2 mm dent; 90th
// 0.11 mm), while the median (0.025 mm) leaves the coarser tenth of the surface beyond it.
double tessellation_level(std::vector<float> tolerance) {
    std::erase_if(tolerance, [](float t) { return !std::isfinite(t); });
    if (tolerance.empty()) return 0.0;
    const auto k = static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(tolerance.size() - 1));
    std::nth_element(tolerance.begin(), tolerance.begin() + k, tolerance.end());
    return tolerance[static_cast<std::size_t>(k)];
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
                  Orientation orientation, PictureCaption caption, const ViewMeasurements* measured)
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
                                 .surface_index = result.reference_index}),
          measured_(measured) {
        const std::size_t n = reference.vertex_count();
        const std::vector<float> distance =
            result.distance.size() == n ? result.distance : std::vector<float>(n, kNaN);
        masks_.resize(result.sweep.zooms.size());
        shapes_.reserve(result.sweep.zooms.size());
        for (std::size_t z = 0; z < result.sweep.zooms.size(); ++z) {
            shapes_.push_back(decided_shape(distance, result.decisions[z]));
            const auto& seen = result.sweep.zooms[z].coverage.seen;
            const auto& comparison = result.decisions[z].comparison;
            auto& shown = masks_[z];
            shown.resize(n);
            for (std::size_t v = 0; v < n; ++v)
                shown[v] = !seen[v] ? 0 : comparison.compared(v) ? 1 : 2;
            zooms_.push_back(zoom_content(z));
        }
        find_best_views();
        // Each view's floors, and how much of what it compared it measured beyond them.
        const double tessellation = tessellation_level(result.tolerance);
        for (const auto& pv : result.sweep.plan.views) {
            const ViewMeasurement* m = measurement(pv.view.index);
            const auto& d = result.decisions[static_cast<std::size_t>(pv.view.zoom_index)];
            detail::MeasuredFloor f{.normal = d.normal.value};
            if (m && d.rule == DecisionRule::Fused)
                f.depth = detail::view_depth_floor(*m, std::max(d.shape.value, tessellation),
                                                   d.shape.k > 0 ? d.shape.k : kDepthFloorK);
            floors_.push_back(f);
            share_.push_back(m ? 0.0 : kNaN);  // share_on_compared_surface() counts it
        }
        share_on_compared_surface();
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
        return detail::atlas_overview_png(
            renderer_, {.mesh = &reference_,
                        .fields = &zooms_[0].fields,
                        .legend = &zooms_[0].legend,
                        .limit = scale_.limit,
                        .regions = &result_.decisions[0].regions.regions,
                        .plan = &result_.sweep.plan,
                        .coverage = result_.sweep.zooms[0].coverage.fraction,
                        .name = name,
                        .unit = unit_or_units(result_),
                        .orientation = &orientation_,
                        .footer = detail::footer_lines(result_, footer),
                        .mirror = options_.mirror ? &*options_.mirror : nullptr});
    }

  private:
    ZoomContent zoom_content(std::size_t z) const;
    void find_best_views();
    void share_on_compared_surface();
    const ViewMeasurement* measurement(int view) const {
        return measured_ ? measured_->find(view) : nullptr;
    }
    // The view painted from its own measurement, or from the atlas when it has none.
    detail::PaintedSurface paint_view(const PlannedView& pv, const View& shown, const Frame& frame,
                                      detail::PaintStyle style) const;
    std::string view_title(const PlannedView& pv, const View& shown) const;
    std::string view_caption(const PlannedView& pv) const;
    // A mirror comparison's symmetry plane on a painted view (report/detail/symmetry_plane_trace.h),
    // clear of the regions and of `keep_clear`; where its label fits, if anywhere.
    std::optional<detail::PlaneLabel> draw_plane(Canvas& image, const PlannedView& pv,
                                                 const View& shown, const Frame& frame,
                                                 std::vector<detail::PixelBox> keep_clear) const {
        if (!options_.mirror) return std::nullopt;
        const auto z = static_cast<std::size_t>(pv.view.zoom_index);
        return detail::draw_symmetry_plane(image, frame, shown, reference_, zooms_[z].fields.region,
                                           *options_.mirror, keep_clear);
    }

    Canvas view_picture(const PlannedView& pv, const View& shown, const Frame& frame,
                        const Canvas& blank);
    detail::ChartInput chart_input(std::size_t z) const;
    std::vector<int> mosaic_tiles(std::size_t z) const;

    const Mesh& reference_;
    const AnalysisResult& result_;
    PictureCaption caption_;
    const ExportOptions& options_;
    Orientation orientation_;
    ShapeScale scale_;
    int threads_ = 0;  ///< workers (RenderOptions::threads: 0 = the machine's)
    Renderer renderer_;
    const ViewMeasurements* measured_ = nullptr;
    /// Per zoom, the shape change painted: the signed distance, and in a hole the depth of
    /// the surface gone (decided_shape), so a hole shows its loss, not the distance to its rim.
    std::vector<std::vector<float>> shapes_;
    std::vector<ZoomContent> zooms_;
    // Per zoom: 0 unseen, 1 compared, 2 seen but not compared (the pictures' fields point here).
    std::vector<std::vector<std::uint8_t>> masks_ = {};
    std::set<int> best_;
    std::vector<detail::MeasuredFloor> floors_;  ///< per view
    std::vector<double> share_;  ///< per view: share beyond its floors (NaN: not measured)
};

// Each measured view's share beyond its floor, counted only where the decision compares the
// surface: a border band or unscanned surface (decision/comparison.h) is hatched in the view's
// picture, and its pixels (a partial scan's far side seen through its cut) must not fill the
// chart either. A small picture of each view (kShareSize px) gives each pixel's triangle; a
// triangle counts when all its corners are compared.
void PictureWriter::share_on_compared_surface() {
    const auto& plan = result_.sweep.plan;
    std::vector<View> small;
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < plan.views.size(); ++i) {
        if (measurement(plan.views[i].view.index) == nullptr) continue;
        small.push_back(resized(plan.views[i].view, kShareSize));
        which.push_back(i);
    }
    if (small.empty()) return;
    renderer_.render_views(small, [&](std::size_t k, const Frame& frame) {
        const auto& pv = plan.views[which[k]];
        const auto view = static_cast<std::size_t>(pv.view.index);
        const auto& mask = masks_[static_cast<std::size_t>(pv.view.zoom_index)];
        const auto mp =
            detail::measured_pixels(*measurement(pv.view.index), pv.view, small[k], floors_[view]);
        std::size_t compared = 0, beyond = 0;
        for (std::size_t p = 0; p < frame.primitive_id.size(); ++p) {
            const auto t = frame.primitive_id[p];
            if (t == kNoPrimitive ||
                mp.status[p] != static_cast<std::uint8_t>(MeasuredStatus::Compared))
                continue;
            const auto& tri = reference_.triangles[t];
            if (mask[tri[0]] != 1 || mask[tri[1]] != 1 || mask[tri[2]] != 1) continue;
            ++compared;
            beyond += mp.beyond[p] != 0;
        }
        share_[view] = compared ? static_cast<double>(beyond) / static_cast<double>(compared) : 0.0;
    });
}

ZoomContent PictureWriter::zoom_content(std::size_t z) const {
    const auto& d = result_.decisions[z];
    ZoomContent c{.fields = {shapes_[z], d.regions.region_of_vertex, masks_[z]},
                  .legend = legend_for(result_, z, scale_, options_.mirror.has_value()),
                  .measured_legend = {}};
    c.measured_legend = c.legend;
    c.measured_legend.measured = true;
    auto& lines = c.measured_legend.lines;
    lines.insert(lines.begin(), options_.mirror
                                    ? "depth along the view ray (this side − mirrored other)"
                                    : "depth along the view ray (reference − examined)");
    if (d.rule == DecisionRule::Fused)
        lines.insert(lines.begin() + 1, "depth floor per view: noise, tessellation");
    return c;
}

// The regions' best views, largest regions first (regions are sorted by area).
void PictureWriter::find_best_views() {
    for (std::size_t k = 0; best_.size() < kMaxBestViews; ++k) {
        bool any = false;
        for (const auto& d : result_.decisions)
            if (k < d.regions.regions.size()) {
                any = true;
                const int v = d.regions.regions[k].best_view;
                if (v >= 0 && static_cast<std::size_t>(v) < result_.sweep.plan.views.size() &&
                    best_.size() < kMaxBestViews)
                    best_.insert(v);
            }
        if (!any) break;
    }
}

detail::PaintedSurface PictureWriter::paint_view(const PlannedView& pv, const View& shown,
                                                 const Frame& frame,
                                                 detail::PaintStyle style) const {
    const auto z = static_cast<std::size_t>(pv.view.zoom_index);
    style.limit = scale_.limit;
    const ViewMeasurement* m = measurement(pv.view.index);
    if (!m) return detail::paint_surface(reference_, frame, shown, zooms_[z].fields, style);
    detail::MeasuredPixels px = detail::measured_pixels(
        *m, pv.view, shown, floors_[static_cast<std::size_t>(pv.view.index)]);
    if (options_.mirror)  // this side against the mirror, as the turned result (inspect.h)
        for (float& depth : px.depth) depth = -depth;
    style.measured = &px;
    return detail::paint_surface(reference_, frame, shown, zooms_[z].fields, style);
}

std::string PictureWriter::view_title(const PlannedView& pv, const View& shown) const {
    const View& v = pv.view;
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
    return detail::with_minus_sign(title);
}

// The line under the title: what the view measured beyond its floors, or that it has no
// measurement.
std::string PictureWriter::view_caption(const PlannedView& pv) const {
    const auto i = static_cast<std::size_t>(pv.view.index);
    if (std::isnan(share_[i])) return "the atlas from this view (compared on the GPU: no pixels)";
    const detail::MeasuredFloor& f = floors_[i];
    const MetricDescriptor& m = describe(result_.sweep.options.metric);
    const std::string floors = f.depth > 0 ? "the depth floor " + detail::format_number(f.depth) +
                                                 " " + unit_or_units(result_)
                                           : "the normal floor " + detail::format_number(f.normal) +
                                                 detail::picture_unit_suffix(m.unit);
    char b[200];
    std::snprintf(b, sizeof b, "%s %% of its pixels beyond %s",
                  detail::format_number(100.0 * share_[i]).c_str(), floors.c_str());
    return b;
}

// `blank`: the zoom's framed sheet at the frame's size with no title (its legend drawn once).
Canvas PictureWriter::view_picture(const PlannedView& pv, const View& shown, const Frame& frame,
                                   const Canvas& blank) {
    auto painted = paint_view(pv, shown, frame, {});
    Canvas sheet = blank;
    const std::string title = view_title(pv, shown);
    detail::draw_title(sheet, detail::fit_text(title, 15, sheet.width() - 16));
    const std::string unit = unit_or_units(result_);
    const std::string caption = detail::fit_text(view_caption(pv), 12, frame.width - 12);
    const auto label =
        draw_plane(painted.image, pv, shown, frame,
                   {detail::view_scale_bar_box(shown, unit), detail::text_box(caption, 12, 6, 16)});
    sheet.paste(painted.image, 0, detail::kTitleHeight);
    detail::draw_plane_label(sheet, 0, detail::kTitleHeight, label);
    detail::draw_text(sheet, 6, detail::kTitleHeight + 16, caption, 12, detail::kText,
                      detail::TextAlign::Left, 2);
    detail::draw_region_numbers(
        sheet, 0, detail::kTitleHeight, frame.width, frame.height, painted.anchors, 14, 30,
        {detail::view_scale_bar_box(shown, unit), detail::text_box(caption, 12, 6, 16)});
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
    // Per zoom and kind (measured or atlas): every view of a zoom has one size.
    std::map<std::pair<std::size_t, bool>, Canvas> blank;
    const auto blank_key = [&](const PlannedView& pv) {
        return std::pair{static_cast<std::size_t>(pv.view.zoom_index),
                         measurement(pv.view.index) != nullptr};
    };
    for (int i : wanted) {
        const auto& pv = plan.views[static_cast<std::size_t>(i)];
        const auto z = static_cast<std::size_t>(pv.view.zoom_index);
        shown.push_back(
            upright(resized(pv.view, std::clamp(plan.sizes[z], kViewMin, kViewMax)), orientation_));
        const auto key = blank_key(pv);
        if (!blank.count(key))
            blank.emplace(key, detail::framed_sheet(
                                   shown.back().camera.width, shown.back().camera.height, "",
                                   key.second ? zooms_[z].measured_legend : zooms_[z].legend));
    }
    // Painted and encoded on every worker; the best views' PNGs kept for the report page.
    std::vector<std::string> kept(detail::batch_size(threads_));
    detail::render_in_batches(
        renderer_, shown, threads_,
        [&](std::size_t slot, std::size_t k, const Frame& frame) {
            const auto& pv = plan.views[static_cast<std::size_t>(wanted[k])];
            const Canvas& sheet = blank.at(blank_key(pv));
            std::string png = encode_png(view_picture(pv, shown[k], frame, sheet));
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

detail::ChartInput PictureWriter::chart_input(std::size_t z) const {
    const auto& plan = result_.sweep.plan;
    const bool rotary = plan.options.kind == SweepPlanOptions::Kind::Rotary;
    detail::ChartInput in;
    if (rotary) {
        in.column_title = "azimuth";
        in.row_title = "elevation";
        for (int c = 0; c < plan.columns; ++c)
            in.column_labels.push_back(detail::format_degrees(c * plan.options.azimuth_step_deg));
        for (double el : plan.options.elevations_deg)
            in.row_labels.push_back(detail::format_degrees(el, true));
    } else {
        in.column_title = "view, in plan order (row start + column)";
        in.row_title = "row start";
        for (int c = 0; c < plan.columns; ++c) in.column_labels.push_back(std::to_string(c));
        for (int r = 0; r < plan.rows; ++r)
            in.row_labels.push_back(std::to_string(r * plan.columns));
    }
    const auto& regions = result_.decisions[z].regions.regions;
    for (const auto& pv : plan.views) {
        if (static_cast<std::size_t>(pv.view.zoom_index) != z) continue;
        detail::ChartCell cell{.column = rotary ? pv.step : pv.step % plan.columns,
                               .row = rotary ? pv.ring : pv.step / plan.columns};
        const double share = share_[static_cast<std::size_t>(pv.view.index)];
        cell.measured = !std::isnan(share);
        cell.share = cell.measured ? share : 0.0;
        for (const auto& r : regions)
            if (r.best_view == pv.view.index) cell.best_of.push_back(r.id);
        in.cells.push_back(std::move(cell));
    }
    return in;
}

// The views a mosaic draws whole: the regions' best views (largest regions first), then the
// views that measured the largest share beyond the floor.
std::vector<int> PictureWriter::mosaic_tiles(std::size_t z) const {
    std::vector<int> tiles;
    const auto add = [&](int v) {
        if (tiles.size() < kMaxTiles && std::find(tiles.begin(), tiles.end(), v) == tiles.end())
            tiles.push_back(v);
    };
    for (const auto& r : result_.decisions[z].regions.regions)
        if (r.best_view >= 0) add(r.best_view);
    std::vector<std::pair<double, int>> ranked;
    for (const auto& pv : result_.sweep.plan.views) {
        const double share = share_[static_cast<std::size_t>(pv.view.index)];
        if (static_cast<std::size_t>(pv.view.zoom_index) == z && share > 0)
            ranked.emplace_back(-share, pv.view.index);
    }
    std::sort(ranked.begin(), ranked.end());
    for (const auto& [negative_share, v] : ranked) add(v);
    return tiles;
}

std::string PictureWriter::mosaic(std::size_t z) {
    const auto& plan = result_.sweep.plan;
    const int t = options_.mosaic_tile;
    const Canvas chart = detail::view_chart(chart_input(z));
    const std::vector<int> tiles = mosaic_tiles(z);
    std::vector<View> shown;
    for (int v : tiles)
        shown.push_back(
            upright(resized(plan.views[static_cast<std::size_t>(v)].view, t), orientation_));
    const int per_row = std::max(kTilesPerRow, (chart.width() + kGap) / (t + kGap));
    const int tile_rows = (static_cast<int>(tiles.size()) + per_row - 1) / per_row;
    const int width = std::max(chart.width(), per_row * (t + kGap));
    const int height = chart.height() + tile_rows * (t + kTileCaption + kGap) + kGap;
    const bool measured =
        std::any_of(share_.begin(), share_.end(), [](double s) { return !std::isnan(s); });
    char title[220];
    std::snprintf(title, sizeof title,
                  "zoom %zu (%s %s/px): what each view measured beyond its floor; %zu region(s), "
                  "%zu view(s) drawn",
                  z, detail::format_number(plan.footprints[z]).c_str(),
                  unit_or_units(result_).c_str(), result_.decisions[z].regions.regions.size(),
                  tiles.size());
    Canvas sheet = detail::framed_sheet(width, height, detail::fit_text(title, 15, width + 250),
                                        measured ? zooms_[z].measured_legend : zooms_[z].legend);
    sheet.paste(chart, 0, detail::kTitleHeight);
    const int tiles_top = detail::kTitleHeight + chart.height() + kGap;
    std::vector<detail::PaintedSurface> painted(detail::batch_size(threads_));
    std::vector<std::optional<detail::PlaneLabel>> labels(painted.size());
    const std::string unit = unit_or_units(result_);
    detail::render_in_batches(
        renderer_, shown, threads_,
        [&](std::size_t slot, std::size_t k, const Frame& frame) {
            const auto& pv = plan.views[static_cast<std::size_t>(tiles[k])];
            painted[slot] =
                paint_view(pv, shown[k], frame, {.outline_width = 1, .hatch_period = 5});
            labels[slot] = draw_plane(painted[slot].image, pv, shown[k], frame,
                                      {detail::view_scale_bar_box(shown[k], unit)});
        },
        [&](std::size_t slot, std::size_t k) {
            const PlannedView& pv = plan.views[static_cast<std::size_t>(tiles[k])];
            const Canvas& tile = painted[slot].image;
            const int x = static_cast<int>(k) % per_row * (t + kGap);
            const int y = tiles_top + static_cast<int>(k) / per_row * (t + kTileCaption + kGap);
            sheet.paste(painted[slot].image, x, y);
            detail::draw_plane_label(sheet, x, y, labels[slot]);
            detail::draw_region_numbers(sheet, x, y, tile.width(), tile.height(),
                                        painted[slot].anchors, 12, 8,
                                        {detail::view_scale_bar_box(shown[k], unit)});
            detail::draw_view_scale_bar(sheet, x, y, shown[k], unit);
            const double share = share_[static_cast<std::size_t>(pv.view.index)];
            char caption[120];
            std::snprintf(caption, sizeof caption, "view %d: %s, %s%s", pv.view.index,
                          detail::format_degrees(pv.view.azimuth_deg).c_str(),
                          detail::format_degrees(pv.view.elevation_deg, true).c_str(),
                          std::isnan(share)
                              ? ""
                              : (", " + detail::format_number(100.0 * share) + " %").c_str());
            detail::draw_text(sheet, x + 2, y + tile.height() + 13,
                              detail::fit_text(caption, 11, t - 4), 11, detail::kDimText);
        });
    return encode_png(sheet);
}

}  // namespace

ShapeScale shape_scale(const AnalysisResult& result) {
    ShapeScale s;
    if (!result.decisions.empty() && result.decisions[0].rule == DecisionRule::Fused)
        s.floor = result.decisions[0].shape.value;
    // note: the median, not the largest: one large change (a resection, a misfit part) would
    // leave every other region pale; changes beyond the range are drawn at full colour.
    // Surface gone counts only when every region is (worn cusps): a resection stood tens of
    // millimetres above its rim and would leave a 3 mm bump white; it is drawn at full colour.
    std::vector<double> peaks, gone;
    if (!result.decisions.empty())
        for (const auto& r : result.decisions[0].regions.regions)
            if (r.kind != RegionKind::MissingSurface && std::isfinite(r.peak_depth))
                (r.is_hole_loss() ? gone : peaks).push_back(std::abs(r.peak_depth));
    if (peaks.empty()) peaks = gone;
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
                             const AnalysisObserver& observer, const ViewMeasurements* measured) {
    PictureOutput out;
    if (result.sweep.zooms.empty() || result.decisions.size() != result.sweep.zooms.size())
        return out;
    PictureWriter writer(reference, result, options, orientation, caption, measured);
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
