#include "scanner/view_exports.h"

#include "scanner/images.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace glint {

namespace fs = std::filesystem;

struct ViewExporter::Impl {
    const OutputFolder* folder = nullptr;
    const SweepPlan* plan = nullptr;
    const MetricDescriptor* metric = nullptr;
    ExportOptions options;
    std::vector<Mosaic> mosaics;
    ColorScale scale;

    void write_exr(const std::string& name, const PlannedView& pv, const DeviationMap& dev) const;
};

ViewExporter::ViewExporter(const OutputFolder& folder, const SweepPlan& plan, Metric metric, const ExportOptions& options)
    : impl_(std::make_unique<Impl>()) {
    impl_->folder = &folder;
    impl_->plan = &plan;
    impl_->metric = &describe(metric);
    impl_->options = options;
    impl_->scale.high = impl_->metric->color_max;
    impl_->scale.unit = " " + std::string(impl_->metric->unit);
    for (std::size_t z = 0; z < plan.footprints.size(); ++z) {
        char title[192];
        std::snprintf(title, sizeof title, "%s, zoom %zu (footprint %.4g per px, %d px)",
                      std::string(impl_->metric->title).c_str(), z, plan.footprints[z], plan.sizes[z]);
        impl_->mosaics.emplace_back(plan.columns, plan.rows, options.mosaic_tile, title);
    }
}

ViewExporter::~ViewExporter() = default;

void ViewExporter::Impl::write_exr(const std::string& name, const PlannedView& pv, const DeviationMap& dev) const {
    const View& v = pv.view;
    std::vector<float> sil(dev.silhouette.begin(), dev.silhouette.end());
    char az[32], el[32], fp[32];
    std::snprintf(az, sizeof az, "%.6g", v.azimuth_deg);
    std::snprintf(el, sizeof el, "%.6g", v.elevation_deg);
    std::snprintf(fp, sizeof fp, "%.6g", v.footprint);
    std::vector<std::string> names{"angle_deg", "signed_depth", "silhouette"};
    std::vector<const std::vector<float>*> channels{&dev.angle_deg, &dev.signed_depth, &sil};
    if (metric->id != Metric::AngleDeg) {  // the sweep's own metric, beside the angle
        names.push_back(std::string(metric->name) + "_" + std::string(metric->unit));
        channels.push_back(&dev.value);
    }
    write_exr_channels(folder->file(fs::path("views") / (name + ".exr")), dev.width, dev.height, names, channels,
                       {{"azimuth_deg", az}, {"elevation_deg", el}, {"footprint", fp},
                        {"metric", std::string(metric->name)},
                        {"silhouette_codes", "0 same, 1 reference only, 2 examined only"}});
}

void ViewExporter::add(const PlannedView& pv, const Frame&, const Frame&, const DeviationMap& dev) {
    auto& impl = *impl_;
    const View& v = pv.view;
    ScalarImage img{dev.width, dev.height, dev.value};
    // Silhouette changes show at full scale: surface missing or added there.
    for (std::size_t i = 0; i < img.values.size(); ++i)
        if (dev.silhouette[i] != 0) img.values[i] = static_cast<float>(impl.scale.high);
    char name[96];
    std::snprintf(name, sizeof name, "z%d_az%05.1f_el%+05.1f", v.zoom_index, v.azimuth_deg, v.elevation_deg);
    char label[64];
    std::snprintf(label, sizeof label, "%.0f/%+.0f", v.azimuth_deg, v.elevation_deg);
    const bool rotary = impl.plan->options.kind == SweepPlanOptions::Kind::Rotary;
    const int col = rotary ? pv.step : pv.step % impl.plan->columns;
    const int row = rotary ? pv.ring : pv.step / impl.plan->columns;
    impl.mosaics[static_cast<std::size_t>(v.zoom_index)].place(col, row, img, impl.scale, rotary ? "" : label);
    if (impl.options.write_views) {
        double max_value = 0.0;
        for (float x : dev.value)
            if (x == x) max_value = std::max(max_value, static_cast<double>(x));
        char title[192];
        std::snprintf(title, sizeof title, "view %d: azimuth %.1f, elevation %+.1f, zoom %d, max %s %.2f%s", v.index,
                      v.azimuth_deg, v.elevation_deg, v.zoom_index, std::string(impl.metric->name).c_str(), max_value,
                      std::string(impl.metric->symbol).c_str());
        write_heatmap_png(img, impl.scale, title, impl.folder->file(fs::path("views") / (std::string(name) + ".png")));
    }
    if (impl.options.write_exr) impl.write_exr(name, pv, dev);
}

void ViewExporter::finish() {
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
