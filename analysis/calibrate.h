// Calibration, the paper's first use: an expert's referential deformation sets the
// threshold. The referential case (a surface and the same surface with the referential
// deformation) is swept at a ladder of footprints, fine to coarse, with one angle
// threshold; the calibration footprint is the finest one at which the deformation no longer
// shows. Sweeping at that footprint then flags only deformations larger than the
// referential one: footprint averaging hides whatever is smaller.
#pragma once

#include "analysis/analysis.h"
#include "mesh/mesh.h"

#include <filesystem>
#include <string>
#include <vector>

namespace glint {

struct CalibrationOptions {
    double threshold_deg = 3.0;  ///< the angle a deformation must reach to show
    double finest = 0.0;         ///< footprint, mesh units per pixel; 0 = framing radius / 256
    double coarsest = 0.0;       ///< 0 = framing radius / 3
    double step = 1.4;           ///< ratio between rungs of the ladder (> 1)
    void validate() const;
};

struct CalibrationRung {
    double footprint = 0.0;
    std::size_t regions = 0;
    double max_angle_deg = 0.0;  ///< strongest per-vertex mean angle seen
};

struct Calibration {
    bool found = false;      ///< false: the deformation shows even at the coarsest rung
    double footprint = 0.0;  ///< the finest footprint at which the referential case shows nothing
    double threshold_deg = 0.0;
    std::string referential;  ///< description of the referential case
    std::vector<CalibrationRung> ladder;
};

/// Analyses the referential case (fitted as `analysis.fit` says) at every rung of the
/// ladder in one sweep, with the calibration's threshold given. \throw InputError invalid
/// options; the analysis' errors.
[[nodiscard]] Calibration calibrate(const Mesh& reference, const Mesh& examined,
                                    AnalysisOptions analysis, const CalibrationOptions& options,
                                    const std::string& referential);

}  // namespace glint
