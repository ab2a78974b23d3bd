// Keyword arguments of the Python functions → glint's option structs.
//
// Each keyword sets one field through the parser the command line and scenario files use
// (parse_roi, parse_metric, …), so the three agree on spellings; a keyword left out keeps the
// library's default (there are no defaults in Python to drift from C++). The keywords are the
// command line's flags without dashes, dashes as underscores (--azimuth-step → azimuth_step);
// glint sweep's --fit-roi is fit_roi everywhere (the sweep's own ROI is roi).
#pragma once

#include "scanner/analysis.h"
#include "volume/surface.h"

#include <pybind11/pybind11.h>

#include <string>

namespace glint::python {

/// What keywords can set.
struct Keywords {
    AnalysisOptions analysis;
    SurfaceOptions surface;
};

/// Which keywords a function accepts.
enum KeywordGroup : unsigned {
    kSurfaceKeywords =
        1u << 0,  ///< iso, surface_roi, largest, seed, smooth, passband, edge, tolerance
    kFitKeywords =
        1u << 1,  ///< loss, fit_roi, landmarks, init, samples, max_iterations, symmetric, coarse
    kUnitKeywords = 1u << 2,  ///< unit, allow_scale_mismatch
    kSweepKeywords =
        1u << 3,  ///< plan, azimuth_step, elevations, zoom, roi, size, supersample, metric,
                  ///< backend, device, max_incidence
    kDecisionKeywords =
        1u << 4,  ///< rule, threshold_deg, noise_k, min_threshold_deg, shape_threshold,
                  ///< min_region_vertices
    kExportKeywords = 1u << 5,  ///< views, exr, force
};

/// Applies `kwargs` to `into`. \throw pybind11::type_error for a keyword the function does not
/// take (naming the ones it does); InputError naming the keyword for a value of the wrong type
/// or one its parser refuses.
void apply_keywords(Keywords& into, const pybind11::kwargs& kwargs, unsigned groups,
                    const std::string& function);

/// The keywords of `groups`, comma-separated (for docstrings and errors).
[[nodiscard]] std::string keyword_names(unsigned groups);

}  // namespace glint::python
