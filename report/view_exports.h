// Per-view numbers written while a sweep runs: an EXR per view with the raw comparison
// (views/z<k>_az<A>_el<E>.exr: angle, signed depth, silhouette, the metric). The pictures
// (per-view PNGs, mosaics, atlas.png) show regions, so they are drawn after the decision:
// report/pictures.h.
#pragma once

#include "render/frame.h"
#include "report/export_options.h"
#include "report/output_folder.h"
#include "scanner/compare.h"
#include "scanner/metric.h"
#include "scanner/plan.h"

namespace glint {

class ViewExporter {
  public:
    ViewExporter(const OutputFolder& folder, Metric metric, const ExportOptions& options);
    ViewExporter(const ViewExporter&) = delete;
    ViewExporter& operator=(const ViewExporter&) = delete;
    /// Writes the view's EXR when ExportOptions::write_exr (a ViewObserver's work). \throw IoError.
    void add(const PlannedView& view, const DeviationMap& deviation);

  private:
    const OutputFolder* folder_;
    const MetricDescriptor* metric_;
    ExportOptions options_;
};

}  // namespace glint
