#include "analysis/calibrate.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace glint {

void CalibrationOptions::validate() const {
    auto bad = [](const std::string& field, double v, const std::string& rule) {
        std::ostringstream s;
        s << "calibration: " << field << " = " << v << ": " << rule;
        throw InputError(s.str());
    };
    if (!(threshold_deg > 0 && threshold_deg < 90))
        bad("threshold", threshold_deg, "must be in (0, 90) degrees");
    if (finest < 0) bad("finest footprint", finest, "must be ≥ 0 (0 = automatic)");
    if (coarsest < 0) bad("coarsest footprint", coarsest, "must be ≥ 0 (0 = automatic)");
    if (finest > 0 && coarsest > 0 && !(coarsest > finest))
        bad("coarsest footprint", coarsest, "must exceed the finest");
    if (!(step > 1.05)) bad("step", step, "must be > 1.05");
}

Calibration calibrate(const Mesh& reference, const Mesh& examined, AnalysisOptions analysis,
                      const CalibrationOptions& options, const std::string& referential) {
    options.validate();
    // The ladder, fine to coarse, framed as the sweep frames the mesh.
    SweepPlanOptions probe = analysis.sweep.plan;
    probe.footprints.clear();
    if (probe.roi && probe.roi->needs_mask()) read_roi_mask(*probe.roi, reference.vertex_count());
    const double radius = make_sweep_plan(reference, probe).radius;
    const double finest = options.finest > 0 ? options.finest : radius / 256.0;
    const double coarsest = options.coarsest > 0 ? options.coarsest : radius / 3.0;
    std::vector<double> ladder;
    for (double f = finest; f <= coarsest * 1.0001; f *= options.step) ladder.push_back(f);
    analysis.sweep.plan.footprints = ladder;
    analysis.decision.threshold = options.threshold_deg;
    const AnalysisResult result = analyse(reference, examined, analysis);

    Calibration c;
    c.threshold_deg = options.threshold_deg;
    c.referential = referential;
    for (std::size_t z = 0; z < result.sweep.zooms.size(); ++z) {
        const auto& zoom = result.sweep.zooms[z];
        CalibrationRung rung{result.sweep.plan.footprints[z],
                             result.decisions[z].regions.regions.size(), 0.0};
        for (std::size_t v = 0; v < zoom.coverage.seen.size(); ++v)
            if (zoom.coverage.seen[v])
                rung.max_angle_deg = std::max(rung.max_angle_deg, double(zoom.atlas.value_mean[v]));
        c.ladder.push_back(rung);
    }
    // The finest rung from which the deformation stays hidden at every coarser rung.
    for (std::size_t i = c.ladder.size(); i-- > 0;) {
        if (c.ladder[i].regions != 0) break;
        c.found = true;
        c.footprint = c.ladder[i].footprint;
    }
    return c;
}

}  // namespace glint
