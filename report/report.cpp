#include "report/report.h"

#include "mesh/atomic_file.h"
#include "mesh/checksum.h"
#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/units.h"
#include "mesh/version.h"
#include "mesh/write.h"
#include "report/atlas_fields.h"
#include "report/detail/options_json.h"
#include "report/finding.h"
#include "report/orientation.h"
#include "report/pictures.h"
#include "report/report_html.h"
#include "scanner/coverage.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <future>
#include <limits>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

namespace glint {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json vec_json(const Vec3d& v) { return json::array({v.x(), v.y(), v.z()}); }

// JSON has no NaN: report non-finite numbers as null.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The region in words (report/finding.h): where it lies, which way it faces, one sentence.
struct RegionWords {
    const Bounds* reference = nullptr;
    const Orientation* orientation = nullptr;
    double depth_uncertainty = 0.0;
    std::string unit;
    bool mirror = false;  ///< this side against the mirrored other side
};

json region_json(const Region& r, const SweepPlan& plan, const MetricDescriptor& m,
                 double peak_value, const RegionWords& words) {
    const std::string u = "_" + std::string(m.unit);
    const std::string nu = "_" + std::string(m.name) + u;
    json j = {
        {"id", r.id},
        {"kind", to_string(r.kind)},
        {"vertices", r.vertex_count},
        {"area", r.area},
        {"max" + u, r.max_value},  // kept for readers: the largest per-vertex mean (max_mean_…)
        {"mean" + u, r.mean_value},
        {"max_mean" + nu, r.max_value},
        {"mean" + nu, r.mean_value},
        {"max" + nu, number(peak_value)},
        {"peak_depth", number(r.peak_depth)},
        {"mean_depth", number(r.mean_depth)},
        {"volume", number(r.volume)},
        {"missing_fraction", r.missing_fraction},
        {"centroid", vec_json(r.centroid)},
        {"evidence", r.evidence},
        // a loss where the examined surface covered around it (decision/comparison.h): material
        // gone, not a part never scanned (that is comparison.not_compared.not_reached)
        {"surface_gone", r.is_hole_loss()},
        // how strongly it stands out from the undamaged surface (decision.cpp
        // state_significance): null where it is no distance (surface gone, missing surface)
        {"z", number(r.z)},
        {"p_value", number(r.p_value)},
        // the radius its evidence was read over (0: each vertex's own; decision.h EvidenceScale)
        {"scale_radius", r.scale_radius},
        {"best_view", r.best_view}};
    if (r.kind == RegionKind::MissingSurface) {
        // The examined scan holds no surface there: a depth or volume would measure to
        // nothing, so none is given (its area and kind are what is known).
        j["peak_depth"] = nullptr;
        j["mean_depth"] = nullptr;
        j["volume"] = nullptr;
        j["depth_note"] = std::string(kMissingSurfaceNote);
    } else if (r.is_hole_loss()) {
        j["depth_note"] = std::string(kHoleLossNote);
    }
    if (r.best_view >= 0 && static_cast<std::size_t>(r.best_view) < plan.views.size()) {
        const auto& v = plan.views[static_cast<std::size_t>(r.best_view)].view;
        j["best_view_azimuth_deg"] = v.azimuth_deg;
        j["best_view_elevation_deg"] = v.elevation_deg;
    }
    // The direction its close-up looks from (analysis/region_views.h): the most of it face on
    // and unoccluded, the share of its area seen projected from there.
    if (r.view_direction.norm() > 0.5) {
        j["view_direction"] = vec_json(r.view_direction);
        j["visible_fraction"] = r.visible_fraction;
    }
    if (words.reference && words.orientation) {
        const std::string place = region_place(r, *words.reference, *words.orientation);
        j["place"] = place;
        // Its own scale's spread where the decision measured one (a region found over a wider
        // disc reads a smaller one), else the zoom's.
        const double sd = std::isfinite(r.depth_sd) ? r.depth_sd : words.depth_uncertainty;
        j["depth_uncertainty"] = sd;
        j["finding"] = region_sentence(r, place, sd, words.unit, words.mirror);
    }
    return j;
}

// The largest per-vertex maximum (the strongest pixel deviation seen) in each region, by
// region id; NaN for a region without seen vertices.
std::vector<double> region_peak_values(const AnalysisResult& result, std::size_t z) {
    const auto& d = result.decisions[z];
    const auto& atlas = result.sweep.zooms[z].atlas;
    const auto& seen = result.sweep.zooms[z].coverage.seen;
    std::vector<double> peak(d.regions.regions.size() + 1, std::nan(""));
    for (std::size_t v = 0; v < d.regions.region_of_vertex.size(); ++v) {
        const auto id = d.regions.region_of_vertex[v];
        if (id <= 0 || static_cast<std::size_t>(id) >= peak.size() || !seen[v]) continue;
        double& p = peak[static_cast<std::size_t>(id)];
        p = std::isnan(p) ? atlas.value_max[v]
                          : std::max(p, static_cast<double>(atlas.value_max[v]));
    }
    return peak;
}

json unseen_json(const Mesh& reference, const SweepZoom& z, const SweepPlan& plan) {
    const UnseenSummary u = unseen_patches(reference, z.coverage.seen, plan.options.roi);
    json list = json::array();
    for (const auto& p : u.patches) {
        if (list.size() >= 50) break;
        list.push_back(
            {{"vertices", p.vertices}, {"area", p.area}, {"centroid", vec_json(p.centroid)}});
    }
    return {{"vertices", u.vertices},
            {"area", u.area},
            {"patches", u.patches.size()},
            {"largest_patches", list}};
}

json floor_json(const Floor& f) {
    return {{"value", f.value},
            {"low", f.low},
            {"median", f.median},
            {"mad", f.mad},
            {"k", f.k},
            {"minimum", f.minimum},
            {"given", f.given},
            {"implausible", f.implausible},
            {"corroborates", f.corroborates},
            {"source", to_string(f.source)},
            {"rule", f.rule},
            {"note", f.note}};
}

// The scale the fused rule read its evidence at (decision/decision.h EvidenceScale).
json scale_json(const EvidenceScale& s) {
    json j = {{"radius", s.radius},
              {"searched", s.searched},
              {"quiet", s.quiet},
              {"min_detectable_depth", s.min_depth},
              {"min_detectable_area", s.min_area},
              {"radii_tried", s.tried},
              {"wider_radii_searched", s.wider},
              {"resolution_depth", s.resolution_depth},
              {"resolution_elements", s.resels},
              {"text", s.text}};
    // The smallest detectable damage at each scale from the one read (EvidenceScale::limit_curve).
    json curve = json::array();
    for (const auto& p : s.limit_curve)
        curve.push_back({{"radius", p.radius},
                         {"area", number(p.area)},
                         {"depth", number(p.depth)},
                         {"depth_across_slices", number(p.depth_across)}});
    j["detection_limit"] = curve;
    // The distance read per band of the grid's staircase step along the normal (decision.cpp): each
    // band's spread, and the smallest detectable depth where faces lie across thick slices.
    if (!s.sampling_bands.empty()) {
        j["sampling_band_spreads"] = s.sampling_bands;
        j["min_detectable_depth_across_slices"] = s.min_depth_across;
    }
    if (s.searched) {
        j["own_scale_normal_floor"] = floor_json(s.own_normal);
        j["own_scale_shape_floor"] = floor_json(s.own_shape);
    }
    return j;
}

// How each part of the reference was classified (decision/comparison.h): areas per class.
json comparison_json(const Comparison& c) {
    const auto share = [&](double a) { return c.reference_area > 0 ? a / c.reference_area : 0.0; };
    const auto entry = [&](double a) { return json{{"area", a}, {"share", share(a)}}; };
    json scan = nullptr;  // the examined surface is no one-view scan
    if (c.scan_view)
        scan = {
            {"direction",
             {c.scan_view->direction.x(), c.scan_view->direction.y(), c.scan_view->direction.z()}},
            {"cone_deg", c.scan_view->cone_deg},
            {"grazing_deg", kGrazingDeg}};
    return {
        {"rule", c.rule},
        {"band", c.band},
        {"examined_one_view_scan", scan},
        {"examined_encloses", c.examined_encloses},
        {"dropouts", {{"count", c.dropouts}, {"area", c.dropout_area}}},
        {"beyond_examined_field_of_view", {{"count", c.beyond_view}, {"area", c.beyond_view_area}}},
        {"median_edge", c.edge},
        {"reference_area", c.reference_area},
        {"compared_area", c.compared_area},
        {"compared_fraction", c.fraction},
        {"not_compared",
         {{"reference_border", entry(c.reference_border_area)},
          {"examined_border", entry(c.examined_border_area)},
          {"not_reached", entry(c.not_reached_area)},
          {"below_resolution", entry(c.below_resolution_area)}}},
        {"holes",
         {{"count", c.holes},
          {"area", c.hole_area},
          {"losses", {{"count", c.lost_holes}, {"area", c.lost_hole_area}}}}}};
}

json zoom_json(const Mesh& reference, const AnalysisResult& result, std::size_t z,
               const Orientation& orientation, bool mirror) {
    const auto& plan = result.sweep.plan;
    const auto& sz = result.sweep.zooms[z];
    const auto& d = result.decisions[z];
    const MetricDescriptor& m = describe(result.sweep.options.metric);
    const std::string u = "_" + std::string(m.unit);
    json regions = json::array();
    const std::vector<double> peaks = region_peak_values(result, z);
    const Bounds box = bounds(reference);
    // ± one robust standard deviation of the distance on the unchanged surface (the shape
    // floor's spread; none without a shape floor).
    const RegionWords words{
        &box, &orientation,
        d.rule == DecisionRule::Fused && d.shape.mad > 0 ? 1.4826 * d.shape.mad : 0.0, result.unit,
        mirror};
    for (const auto& r : d.regions.regions)
        regions.push_back(region_json(r, plan, m, peaks[static_cast<std::size_t>(r.id)], words));
    json j = {
        {"zoom", z},
        {"footprint", plan.footprints[z]},
        {"image_size", plan.sizes[z]},
        {"coverage", sz.coverage.fraction},
        {"unseen", unseen_json(reference, sz, plan)},
        {"comparison", comparison_json(d.comparison)},
        {"rule", to_string(d.rule)},
        {"rule_text", d.rule_text},
        {"threshold" + u, d.normal.value},
        {"normal_floor", floor_json(d.normal)},
        {"shape_floor", d.rule == DecisionRule::Fused ? floor_json(d.shape) : json(nullptr)},
        {"evidence_scale", d.rule == DecisionRule::Fused ? scale_json(d.scale) : json(nullptr)},
        {"damaged_vertices", d.regions.damaged_vertices},
        {"filled_vertices", d.regions.filled_vertices},
        {"dropped_small_groups", d.regions.dropped_small},
        {"dropped_shallow_groups", d.regions.dropped_shallow},
        {"regions", regions},
        {"histogram",
         {{"of", "per-vertex mean " + std::string(m.name) + " of seen vertices"},
          {"bin_width", m.histogram_bin},
          {"unit", std::string(m.unit)},
          {"last_bin", ">= " + std::to_string(static_cast<int>(m.histogram_max))},
          {"counts", d.histogram}}},
        {"warnings", d.warnings}};
    return j;
}

json inputs_json(const std::vector<InputRecord>& inputs) {
    json list = json::array();
    for (const auto& in : inputs) {
        json j = {{"role", in.role}, {"vertices", in.vertices}, {"triangles", in.triangles}};
        if (!in.path.empty()) {
            j["path"] = in.path.string();
            // The checksum of the bytes the loader read, else the file as it is now.
            j["sha256"] = in.sha256.empty() ? sha256_file(in.path) : in.sha256;
        }
        if (!in.description.empty()) j["description"] = in.description;
        if (!in.space.empty()) j["space"] = in.space;
        list.push_back(j);
    }
    return list;
}

json plan_json(const SweepPlan& plan) {
    return {{"footprints", plan.footprints},     {"image_sizes", plan.sizes},
            {"target", vec_json(plan.target)},   {"radius", plan.radius},
            {"roi_vertices", plan.roi_vertices}, {"views", plan.views.size()}};
}

json views_json(const SweepResult& s) {
    json views = json::array();
    for (const auto& v : s.views) {
        const View& pv = s.plan.views[static_cast<std::size_t>(v.index)].view;
        views.push_back({{"index", v.index},
                         {"azimuth_deg", pv.azimuth_deg},
                         {"elevation_deg", pv.elevation_deg},
                         {"zoom", pv.zoom_index},
                         {"reference_pixels", v.reference_pixels},
                         {"compared", v.compared},
                         {"reference_only", v.reference_only},
                         {"examined_only", v.examined_only},
                         {"max_angle_deg", v.max_angle_deg},
                         {"mean_angle_deg", v.mean_angle_deg}});
    }
    return views;
}

// What every length in this report is measured in, and how that was found.
json units_json(const AnalysisResult& r) {
    const std::string u = r.unit.empty() ? "units" : r.unit;
    return {{"length", u},
            {"area", u + "²"},
            {"volume", u + "³"},
            {"known", !r.unit.empty()},
            {"note",
             r.unit.empty()
                 ? "unknown: the files state no unit and none was given (--unit, scenario key unit)"
                 : "every length, area and volume in this report (depths, distances, footprints, "
                   "centroids, sizes) is in " +
                       r.unit},
            {"reference_size", r.units.reference_size},
            {"examined_size", r.units.examined_size},
            {"examined_scale", r.units.examined_scale}};
}

}  // namespace

namespace {

// How the pictures are oriented: the reference's space and --up.
Orientation run_orientation(const RunRecord& record, const ExportOptions& exports) {
    PatientSpace space = PatientSpace::Unknown;
    for (const auto& in : record.inputs)
        if (in.role == "reference") space = parse_space(in.space);
    return resolve_orientation(space, exports.up);
}

json orientation_json(const Orientation& o) {
    return {{"space", o.space == PatientSpace::Unknown ? json(nullptr) : json(to_string(o.space))},
            {"up", vec_json(o.up)},
            {"up_name", o.name(o.up)},
            {"up_stated", o.up_known},
            {"front", vec_json(o.front)},
            {"front_name", o.name(o.front)},
            {"source", o.source}};
}

}  // namespace

std::string report_json(const Mesh& reference, const AnalysisResult& result,
                        const InspectOptions& options, const RunRecord& record, bool mirror) {
    const auto& s = result.sweep;
    const MetricDescriptor& m = describe(s.options.metric);
    json zooms = json::array();
    const Orientation orientation = run_orientation(record, options.exports);
    for (std::size_t z = 0; z < s.zooms.size(); ++z)
        zooms.push_back(zoom_json(reference, result, z, orientation, mirror));
    json report = {
        {"glint_version", kVersion},
        {"command_line", record.command_line},
        {"inputs", inputs_json(record.inputs)},
        {"device",
         {{"backend", to_string(s.renderer.backend)},
          {"name", s.renderer.device_name},
          {"type", s.renderer.device_type},
          // How Vulkan drew the frames (render/context.h Raster); "auto" for Embree.
          {"raster", to_string(s.renderer.raster)},
          {"warnings", s.renderer.warnings},
          {"compare_on", s.on_gpu ? "gpu" : "cpu"},
          {"compare_note", s.accumulation_note}}},
        {"analysis", detail::options_object(options.analysis, options.exports)},
        {"metric",
         {{"name", std::string(m.name)},
          {"unit", std::string(m.unit)},
          {"description", std::string(m.description)}}},
        {"plan", plan_json(s.plan)},
        {"orientation", orientation_json(orientation)},
        {"size", result.size},
        {"unit", result.unit.empty() ? json(nullptr) : json(result.unit)},
        {"units", units_json(result)},
        {"resolution",
         {{"rule", result.resolution.rule},
          {"voxel", result.voxel},
          {"below_resolution_area", result.resolution.flagged_area},
          {"faint_area", result.resolution.faint_area}}},
        {"fit", result.fit.json.empty() ? json(nullptr) : json::parse(result.fit.json)},
        {"zooms", zooms},
        {"views", views_json(s)},
        {"timings_s",
         {{"fit", result.fit_seconds},
          {"distance", result.distance_seconds},
          {"render", s.render_seconds},
          {"compare_and_atlas", s.compare_seconds},
          {"sweep_total", s.total_seconds},
          {"decision", result.decision_seconds},
          {"total", result.total_seconds}}},
        {"warnings", result.warnings},
    };
    return json_text(report, 2) + "\n";
}

std::string regions_csv(const AnalysisResult& result) {
    const MetricDescriptor& m = describe(result.sweep.options.metric);
    const std::string nu = std::string(m.name) + "_" + std::string(m.unit);
    const std::string l = unit_suffix(result.unit), a2 = unit_suffix(result.unit, 2),
                      v3 = unit_suffix(result.unit, 3);
    std::ostringstream csv;
    // max_<metric>: the strongest pixel deviation seen in the region; max_mean_<metric>: the
    // largest per-vertex mean (the field regions are grown on); mean_<metric>: area-weighted.
    csv << "zoom,footprint" << l << "_per_px,region,kind,vertices,area" << a2 << ",max_" << nu
        << ",max_mean_" << nu << ",mean_" << nu << ",peak_depth" << l << ",mean_depth" << l
        << ",volume" << v3 << ",missing_fraction,centroid_x" << l << ",centroid_y" << l
        << ",centroid_z" << l
        << ",best_view,best_view_azimuth_deg,best_view_elevation_deg,z,p_value,scale_radius" << l
        << "\n";
    const auto& plan = result.sweep.plan;
    for (std::size_t z = 0; z < result.decisions.size(); ++z) {
        const std::vector<double> peaks = region_peak_values(result, z);
        for (const auto& r : result.decisions[z].regions.regions) {
            double az = std::nan(""), el = std::nan("");
            if (r.best_view >= 0) {
                az = plan.views[static_cast<std::size_t>(r.best_view)].view.azimuth_deg;
                el = plan.views[static_cast<std::size_t>(r.best_view)].view.elevation_deg;
            }
            // A missing-surface region has no depth and no volume (the examined scan holds no
            // surface there): empty cells, as report.json's nulls.
            char depths[120] = ",,";
            if (r.kind != RegionKind::MissingSurface)
                std::snprintf(depths, sizeof depths, "%.6g,%.6g,%.6g", r.peak_depth, r.mean_depth,
                              r.volume);
            // How strongly it stands out (decision.cpp state_significance): empty where the run
            // stated none (a surface gone, a missing surface, a region at the vertices' scale).
            char significance[64] = ",";
            if (std::isfinite(r.z) && std::isfinite(r.p_value))
                std::snprintf(significance, sizeof significance, "%.4g,%.3g", r.z, r.p_value);
            const std::string kind = r.is_hole_loss() ? "surface gone" : to_string(r.kind);
            char row[760];
            std::snprintf(
                row, sizeof row,
                "%zu,%.6g,%d,%s,%zu,%.6g,%.4f,%.4f,%.4f,%s,%.4f,%.6g,%.6g,%.6g,%d,%.6g,%.6g,%s,%.6g\n",
                z, plan.footprints[z], r.id, kind.c_str(), r.vertex_count, r.area,
                peaks[static_cast<std::size_t>(r.id)], r.max_value, r.mean_value, depths,
                r.missing_fraction, r.centroid.x(), r.centroid.y(), r.centroid.z(), r.best_view, az,
                el, significance, r.scale_radius);
            csv << row;
        }
    }
    return csv.str();
}

namespace {

// The atlas mesh (a copy of the reference with every scalar) lives only while its files are
// written, unless it is kept.
// `written` is told after each file (the caller counts them for its progress).
std::optional<Mesh> write_atlas_files(const OutputFolder& folder, const Mesh& reference,
                                      const AnalysisResult& result, const ExportOptions& exports,
                                      const std::function<void()>& written) {
    Mesh atlas = make_atlas_mesh(reference, result);
    for (const auto& [given, values] : exports.extra_scalars) {
        GLINT_ASSERT(values.size() == reference.vertex_count(),
                     "extra atlas scalar '" + given + "' has the wrong length");
        constexpr std::string_view kUnit = "{unit}";
        const std::string name =
            given.ends_with(kUnit)
                ? given.substr(0, given.size() - kUnit.size()) + unit_suffix(result.unit)
                : given;
        std::vector<float> finite(values);  // no NaN in a viewer's file (atlas_fields.h)
        for (float& x : finite)
            if (!std::isfinite(x)) x = 0.0f;
        atlas.set_scalar(name, std::move(finite));
    }
    // The PLY names every field scalar_<name> (CloudCompare imports no other name) and holds
    // the decision field once more as `quality` (the only scalar MeshLab reads): mesh/write.h.
    WriteOptions viewers;
    viewers.cloudcompare_names = true;
    if (atlas.find_scalar(shape_change_field(result.unit)))
        viewers.quality_scalar = shape_change_field(result.unit);
    const AtlasFiles& files = exports.atlas_files;
    if (files.ply) {
        write_ply(atlas, folder.file("atlas.ply"), viewers);
        written();
    }
    if (files.vtk) {
        write_vtk(atlas, folder.file("atlas.vtk"), viewers);
        written();
    }
    if (files.vtp) {
        write_vtp(atlas, folder.file("atlas.vtp"), viewers);
        written();
    }
    if (!exports.keep_atlas) return std::nullopt;
    return atlas;
}

}  // namespace

std::optional<Mesh> write_outputs(const OutputFolder& folder, const Mesh& reference,
                                  const AnalysisResult& result, const LiveSurface* examined,
                                  const ExportOptions& exports, const RunRecord& record,
                                  const std::string& json_text, const AnalysisObserver& observer,
                                  const ViewMeasurements* measured) {
    const auto stage = [&](std::string_view name) {
        if (observer.stage) observer.stage(name);
    };
    // The atlas files and the report page's data are serial work (number formatting and
    // writing; the decimation of a large mesh for the page): at 2M triangles 0.9 s each, done
    // side by side. The pictures (on every worker) come after, so the picture renderer's BVH
    // is not held with the atlas copy and the decimation (2M: peak 737 instead of ~560 MB
    // resident when all three ran at once). An exception in one job waits for the other. The "pictures"
    // stage lets the caller hand back what the jobs freed (tools/memory.h): the page's thread
    // frees its decimation buffers into a heap of its own, which stays resident otherwise (2M:
    // 614 instead of 453 MB resident under the pictures).
    // Deferred (run where it is read) when no thread can be started: the page is then built
    // after the files, as a run without threads would.
    const auto page_job = [&] { return report_page_data(reference, result, examined); };
    std::future<decltype(page_job())> page_data;
    try {
        page_data = std::async(std::launch::async, page_job);
    } catch (const std::system_error&) {
        page_data = std::async(std::launch::deferred, page_job);
    }
    stage("atlas files");
    const AtlasFiles& kinds = exports.atlas_files;
    const std::size_t files = std::size_t{kinds.ply} + kinds.vtk + kinds.vtp + 2;
    std::size_t done = 0;
    const auto written = [&] {
        if (observer.items) observer.items(++done, files);
    };
    std::optional<Mesh> atlas = write_atlas_files(folder, reference, result, exports, written);
    write_file_atomically(folder.file("regions.csv"), regions_csv(result));
    written();
    write_file_atomically(folder.file("report.json"), json_text);
    written();
    stage("report page");
    ReportPageData page = page_data.get();
    if (exports.write_pictures) stage("pictures");
    PictureCaption caption;
    for (const auto& in : record.inputs) {
        // a file's name; a generated surface's description ("phantom sphere ico 4")
        const std::string name = in.path.empty() ? in.description : in.path.filename().string();
        if (in.role == "reference") caption.reference_name = name;
        if (in.role == "examined") caption.examined_name = name;
    }
    const PictureOutput pictures =
        exports.write_pictures
            ? write_pictures(folder, reference, result, exports, run_orientation(record, exports),
                             caption, observer, measured)
            : PictureOutput{};
    stage("report.html");
    write_file_atomically(folder.file("report.html"),
                          report_html(std::move(page), json_text, pictures));
    return atlas;
}

}  // namespace glint
