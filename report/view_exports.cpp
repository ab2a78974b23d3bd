#include "report/view_exports.h"

#include "report/images.h"
#include "report/pictures.h"

#include <cstdio>
#include <string>
#include <vector>

namespace glint {

namespace fs = std::filesystem;

ViewExporter::ViewExporter(const OutputFolder& folder, Metric metric, const ExportOptions& options)
    : folder_(&folder), metric_(&describe(metric)), options_(options) {}

void ViewExporter::add(const PlannedView& pv, const DeviationMap& dev) {
    if (!options_.write_exr) return;
    const View& v = pv.view;
    std::vector<float> sil(dev.silhouette.begin(), dev.silhouette.end());
    char az[32], el[32], fp[32];
    std::snprintf(az, sizeof az, "%.6g", v.azimuth_deg);
    std::snprintf(el, sizeof el, "%.6g", v.elevation_deg);
    std::snprintf(fp, sizeof fp, "%.6g", v.footprint);
    std::vector<std::string> names{"angle_deg", "signed_depth", "silhouette"};
    std::vector<const std::vector<float>*> channels{&dev.angle_deg, &dev.signed_depth, &sil};
    if (metric_->id != Metric::AngleDeg) {  // the sweep's own metric, beside the angle
        names.push_back(std::string(metric_->name) + "_" + std::string(metric_->unit));
        channels.push_back(&dev.value);
    }
    write_exr_channels(folder_->file(fs::path("views") / (view_file_stem(v) + ".exr")), dev.width,
                       dev.height, names, channels,
                       {{"azimuth_deg", az},
                        {"elevation_deg", el},
                        {"footprint", fp},
                        {"metric", std::string(metric_->name)},
                        {"silhouette_codes", "0 same, 1 reference only, 2 examined only"}});
}

}  // namespace glint
