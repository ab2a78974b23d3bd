// Per-view pictures written while a sweep runs: a heat map PNG with a colour bar and an EXR
// with the raw numbers per view (views/z<k>_az<A>_el<E>.png|.exr), and one mosaic per zoom
// (mosaic_z<k>.png), built tile by tile so no full-size frame is kept. Titles, units and
// colour scales follow the sweep's metric (scanner/metric.h).
#pragma once

#include "render/frame.h"
#include "scanner/analysis.h"
#include "scanner/compare.h"
#include "scanner/metric.h"
#include "scanner/output_folder.h"
#include "scanner/plan.h"

#include <memory>

namespace glint {

class ViewExporter {
public:
    ViewExporter(const OutputFolder& folder, const SweepPlan& plan, Metric metric, const ExportOptions& options);
    ~ViewExporter();
    ViewExporter(const ViewExporter&) = delete;
    ViewExporter& operator=(const ViewExporter&) = delete;
    /// Writes the view's files and places its tile (a ViewObserver's work). \throw IoError.
    void add(const PlannedView& view, const Frame& reference, const Frame& examined, const DeviationMap& deviation);
    /// Writes the mosaics (after the sweep). \throw IoError.
    void finish();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace glint
