#include "scanner/report.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/write.h"
#include "scanner/images.h"

#include <nlohmann/json.hpp>
#include <openssl/evp.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace glint {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

json vec_json(const Vec3d& v) { return json::array({v.x(), v.y(), v.z()}); }

// JSON has no NaN: report non-finite numbers as null.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string zoom_suffix(std::size_t z) { return "_z" + std::to_string(z); }

json region_json(const Region& r, const SweepPlan& plan) {
    json j = {{"id", r.id},
              {"kind", to_string(r.kind)},
              {"vertices", r.vertex_count},
              {"area", r.area},
              {"max_angle_deg", r.max_angle_deg},
              {"mean_angle_deg", r.mean_angle_deg},
              {"max_depth", number(r.max_depth)},
              {"max_distance", number(r.max_distance)},
              {"centroid", vec_json(r.centroid)},
              {"best_view", r.best_view}};
    if (r.best_view >= 0 && static_cast<std::size_t>(r.best_view) < plan.views.size()) {
        const auto& v = plan.views[static_cast<std::size_t>(r.best_view)];
        j["best_view_azimuth_deg"] = v.azimuth_deg;
        j["best_view_elevation_deg"] = v.elevation_deg;
    }
    return j;
}

// Unseen vertices grouped into patches (connected over the mesh), largest first.
json unseen_json(const Mesh& reference, const ZoomResult& z) {
    const std::size_t n = reference.vertex_count();
    std::vector<float> unseen(n);
    std::vector<std::uint8_t> all(n, 1);
    for (std::size_t v = 0; v < n; ++v) unseen[v] = z.seen[v] ? 0.0f : 1.0f;
    const RegionResult patches = find_regions(reference, {&unseen, nullptr, nullptr, nullptr, &all},
                                              RegionOptions{.threshold_deg = 0.5, .min_vertices = 1, .fill_holes = false});
    json list = json::array();
    double area = 0.0;
    for (const auto& p : patches.regions) {
        area += p.area;
        if (list.size() < 50) list.push_back({{"vertices", p.vertex_count}, {"area", p.area}, {"centroid", vec_json(p.centroid)}});
    }
    return {{"vertices", patches.damaged_vertices}, {"area", area}, {"patches", patches.regions.size()},
            {"largest_patches", list}};
}

}  // namespace

std::string sha256_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read \"" + path.string() + "\" to checksum it");
    EVP_MD_CTX* ctx = EVP_MD_CTX_new();
    if (!ctx) throw IoError("SHA-256: cannot create a digest context");
    EVP_DigestInit_ex(ctx, EVP_sha256(), nullptr);
    std::vector<char> buf(1 << 16);
    while (in) {
        in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
        EVP_DigestUpdate(ctx, buf.data(), static_cast<std::size_t>(in.gcount()));
    }
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    EVP_DigestFinal_ex(ctx, digest, &len);
    EVP_MD_CTX_free(ctx);
    std::ostringstream hex;
    for (unsigned int i = 0; i < len; ++i) hex << std::hex << std::setw(2) << std::setfill('0') << int(digest[i]);
    return hex.str();
}

Mesh make_atlas_mesh(const Mesh& reference, const SweepResult& result, const ReportContext& context) {
    Mesh atlas = reference;
    atlas.scalars.clear();
    atlas.labels.clear();
    const std::size_t n = reference.vertex_count();
    for (std::size_t z = 0; z < result.zooms.size(); ++z) {
        const auto& zr = result.zooms[z];
        const auto& a = zr.atlas;
        std::vector<float> angle(n), mean(n), depth(n), count(n), seen(n), region(n);
        for (std::size_t v = 0; v < n; ++v) {
            const bool s = zr.seen[v] != 0;
            angle[v] = s ? a.angle_max_deg[v] : kNaN;
            mean[v] = s ? a.angle_mean_deg[v] : kNaN;
            depth[v] = s ? a.depth_at_max[v] : kNaN;
            count[v] = static_cast<float>(a.count[v]);
            seen[v] = s ? 1.0f : 0.0f;
            region[v] = static_cast<float>(zr.regions.region_of_vertex[v]);
        }
        const auto k = zoom_suffix(z);
        const std::string metric = result.options.metric == Metric::RgbAbs ? "rgb" : "angle";
        atlas.set_scalar(metric + "_max" + k, std::move(angle));
        atlas.set_scalar(metric + "_mean" + k, std::move(mean));
        atlas.set_scalar("depth" + k, std::move(depth));
        atlas.set_scalar("count" + k, std::move(count));
        atlas.set_scalar("seen" + k, std::move(seen));
        atlas.set_scalar("region" + k, std::move(region));
    }
    if (context.distance.size() == n) atlas.set_scalar("distance", context.distance);
    if (!result.zooms.empty()) {
        const auto& z0 = result.zooms[0];
        ColorScale scale;
        scale.high = std::max(2.0 * z0.threshold_deg, 1.0);
        atlas.colors = colorize(atlas.find_scalar((result.options.metric == Metric::RgbAbs ? "rgb" : "angle") +
                                                  std::string("_mean_z0"))->values, scale);
    }
    return atlas;
}

std::string sweep_report_json(const Mesh& reference, const SweepResult& result, const ReportContext& context) {
    const auto& plan = result.plan;
    json inputs = json::array();
    for (const auto& in : context.inputs) {
        json j = {{"role", in.role}, {"vertices", in.vertices}, {"triangles", in.triangles}};
        if (!in.path.empty()) {
            j["path"] = in.path.string();
            j["sha256"] = sha256_file(in.path);
        }
        if (!in.description.empty()) j["description"] = in.description;
        inputs.push_back(j);
    }
    const auto& o = plan.options;
    json views = json::array();
    for (const auto& v : result.views)
        views.push_back({{"index", v.index}, {"azimuth_deg", v.azimuth_deg}, {"elevation_deg", v.elevation_deg},
                         {"zoom", v.zoom_index}, {"size", v.size}, {"reference_pixels", v.reference_pixels},
                         {"compared", v.compared}, {"reference_only", v.reference_only},
                         {"examined_only", v.examined_only}, {"max_angle_deg", v.max_angle_deg},
                         {"mean_angle_deg", v.mean_angle_deg}});
    json zooms = json::array();
    for (std::size_t z = 0; z < result.zooms.size(); ++z) {
        const auto& zr = result.zooms[z];
        json regions = json::array();
        for (const auto& r : zr.regions.regions) regions.push_back(region_json(r, plan));
        zooms.push_back({{"zoom", z},
                         {"footprint", plan.footprints[z]},
                         {"image_size", plan.sizes[z]},
                         {"coverage", zr.coverage},
                         {"unseen", unseen_json(reference, zr)},
                         {"threshold_deg", zr.threshold_deg},
                         {"threshold_rule", zr.threshold_rule},
                         {"noise_floor", {{"median_deg", zr.noise.median}, {"mad_deg", zr.noise.mad},
                                          {"k", zr.noise.k}, {"threshold_deg", zr.noise.threshold}}},
                         {"damaged_vertices", zr.regions.damaged_vertices},
                         {"dropped_small_groups", zr.regions.dropped_small},
                         {"regions", regions},
                         {"histogram_deg", {{"bin_width_deg", 1}, {"last_bin", ">= 90"}, {"counts", zr.histogram}}}});
    }
    json report = {
        {"glint_version", "0.1.0"},
        {"command_line", context.command_line},
        {"inputs", inputs},
        {"device", {{"backend", to_string(result.renderer.backend)}, {"name", result.renderer.device_name},
                    {"type", result.renderer.device_type}, {"warnings", result.renderer.warnings}}},
        {"plan", {{"kind", o.kind == SweepPlanOptions::Kind::Rotary ? "rotary" : "sphere"},
                  {"azimuth_step_deg", o.azimuth_step_deg}, {"elevations_deg", o.elevations_deg},
                  {"sphere_views", o.sphere_views}, {"footprints", plan.footprints}, {"image_sizes", plan.sizes},
                  {"margin", o.margin}, {"target", vec_json(plan.target)}, {"radius", plan.radius},
                  {"roi", o.roi ? json(to_string(*o.roi)) : json(nullptr)}, {"roi_vertices", plan.roi_vertices},
                  {"views", plan.views.size()}}},
        {"analysis", {{"metric", to_string(result.options.metric)},
                      {"metric_unit", result.options.metric == Metric::RgbAbs ? "8-bit colour (0-255)" : "degrees"},
                      {"backend_requested", to_string(result.options.render.backend)},
                      {"device_requested", result.options.render.device},
                      {"supersample", result.options.render.supersample},
                      {"min_coverage", result.options.render.min_coverage},
                      {"max_incidence_deg", result.options.max_incidence_deg},
                      {"threshold_deg", result.options.threshold_deg ? json(*result.options.threshold_deg) : json(nullptr)},
                      {"noise_k", result.options.noise_k},
                      {"min_threshold_deg", result.options.min_threshold_deg},
                      {"min_region_vertices", result.options.min_region_vertices}}},
        {"fit", context.fit_json.empty() ? json(nullptr) : json::parse(context.fit_json)},
        {"zooms", zooms},
        {"views", views},
        {"timings_s", {{"render", result.render_seconds}, {"compare_and_atlas", result.compare_seconds},
                       {"sweep_total", result.total_seconds}}},
        {"warnings", context.warnings},
    };
    return report.dump(2) + "\n";
}

void write_sweep_outputs(const OutputFolder& folder, const Mesh& reference, const SweepResult& result,
                         const ReportContext& context) {
    const Mesh atlas = make_atlas_mesh(reference, result, context);
    write_ply(atlas, folder.file("atlas.ply"));
    write_vtk(atlas, folder.file("atlas.vtk"));

    std::ostringstream csv;
    csv << "zoom,footprint,region,kind,vertices,area,max_angle_deg,mean_angle_deg,max_depth,max_distance,"
           "centroid_x,centroid_y,centroid_z,best_view,best_view_azimuth_deg,best_view_elevation_deg\n";
    for (std::size_t z = 0; z < result.zooms.size(); ++z) {
        for (const auto& r : result.zooms[z].regions.regions) {
            double az = std::nan(""), el = std::nan("");
            if (r.best_view >= 0) {
                az = result.plan.views[static_cast<std::size_t>(r.best_view)].azimuth_deg;
                el = result.plan.views[static_cast<std::size_t>(r.best_view)].elevation_deg;
            }
            char row[512];
            std::snprintf(row, sizeof row, "%zu,%.6g,%d,%s,%zu,%.6g,%.4f,%.4f,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.6g,%.6g\n", z,
                          result.plan.footprints[z], r.id, to_string(r.kind).c_str(), r.vertex_count, r.area,
                          r.max_angle_deg, r.mean_angle_deg, r.max_depth, r.max_distance, r.centroid.x(),
                          r.centroid.y(), r.centroid.z(), r.best_view, az, el);
            csv << row;
        }
    }
    write_file_atomically(folder.file("regions.csv"), csv.str());
    write_file_atomically(folder.file("report.json"), sweep_report_json(reference, result, context));
}

struct SweepExporter::Impl {
    const OutputFolder* folder;
    const SweepPlan* plan;
    Options options;
    std::vector<Mosaic> mosaics;
    ColorScale scale;
};

SweepExporter::SweepExporter(const OutputFolder& folder, const SweepPlan& plan, Options options)
    : impl_(std::make_unique<Impl>()) {
    impl_->folder = &folder;
    impl_->plan = &plan;
    impl_->options = options;
    impl_->scale.high = options.color_max_deg;
    for (std::size_t z = 0; z < plan.footprints.size(); ++z) {
        char title[160];
        std::snprintf(title, sizeof title, "angle deviation, zoom %zu (footprint %.4g per px, %d px)", z,
                      plan.footprints[z], plan.sizes[z]);
        impl_->mosaics.emplace_back(plan.columns, plan.rows, options.mosaic_tile, title);
    }
}

SweepExporter::~SweepExporter() = default;

ViewObserver SweepExporter::observer() {
    return [this](const PlannedView& v, const Frame&, const Frame&, const DeviationMap& dev) {
        auto& impl = *impl_;
        ScalarImage img{dev.width, dev.height, dev.angle_deg};
        // Silhouette changes show at full scale: surface missing or added there.
        for (std::size_t i = 0; i < img.values.size(); ++i)
            if (dev.silhouette[i] != 0) img.values[i] = static_cast<float>(impl.scale.high);
        char name[96];
        std::snprintf(name, sizeof name, "z%d_az%05.1f_el%+05.1f", v.zoom_index, v.azimuth_deg, v.elevation_deg);
        char label[64];
        std::snprintf(label, sizeof label, "%.0f/%+.0f", v.azimuth_deg, v.elevation_deg);
        const bool rotary = impl.plan->options.kind == SweepPlanOptions::Kind::Rotary;
        const int col = rotary ? v.step : v.step % impl.plan->columns;
        const int row = rotary ? v.ring : v.step / impl.plan->columns;
        impl.mosaics[static_cast<std::size_t>(v.zoom_index)].place(col, row, img, impl.scale, rotary ? "" : label);
        if (impl.options.write_views) {
            char title[160];
            std::snprintf(title, sizeof title, "view %d: azimuth %.1f, elevation %+.1f, zoom %d, max %.2f deg", v.index,
                          v.azimuth_deg, v.elevation_deg, v.zoom_index, dev.max_angle_deg);
            write_heatmap_png(img, impl.scale, title, impl.folder->file(fs::path("views") / (std::string(name) + ".png")));
        }
        if (impl.options.write_exr) {
            std::vector<float> sil(dev.silhouette.begin(), dev.silhouette.end());
            char az[32], el[32], fp[32];
            std::snprintf(az, sizeof az, "%.6g", v.azimuth_deg);
            std::snprintf(el, sizeof el, "%.6g", v.elevation_deg);
            std::snprintf(fp, sizeof fp, "%.6g", v.footprint);
            std::vector<std::string> names{"angle_deg", "signed_depth", "silhouette"};
            std::vector<const std::vector<float>*> channels{&dev.angle_deg, &dev.signed_depth, &sil};
            if (!dev.rgb_abs.empty()) {  // the paper's metric, when the sweep uses it
                names.emplace_back("rgb_abs");
                channels.push_back(&dev.rgb_abs);
            }
            write_exr_channels(impl.folder->file(fs::path("views") / (std::string(name) + ".exr")), dev.width,
                               dev.height, names, channels,
                               {{"azimuth_deg", az}, {"elevation_deg", el}, {"footprint", fp},
                                {"silhouette_codes", "0 same, 1 reference only, 2 examined only"}});
        }
    };
}

void SweepExporter::finish() {
    const auto& plan = *impl_->plan;
    std::vector<std::string> cols, rows;
    if (plan.options.kind == SweepPlanOptions::Kind::Rotary) {
        for (int c = 0; c < plan.columns; ++c) {
            char b[32];
            std::snprintf(b, sizeof b, "az %.0f", c * plan.options.azimuth_step_deg);
            cols.push_back(b);
        }
        for (double e : plan.options.elevations_deg) {
            char b[32];
            std::snprintf(b, sizeof b, "el %+.0f", e);
            rows.push_back(b);
        }
    }
    for (std::size_t z = 0; z < impl_->mosaics.size(); ++z)
        impl_->mosaics[z].write(impl_->folder->file("mosaic_z" + std::to_string(z) + ".png"), impl_->scale, cols, rows);
}

}  // namespace glint
