// Fitting the examined mesh into the reference frame before a sweep, and the per-vertex
// signed distance channel of the atlas. Wraps registration/ so that the command line and the
// scenario runner ask for a fit the same way.
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"

#include <filesystem>
#include <string>
#include <vector>

namespace glint {

struct FitRequest {
    enum class Mode {
        Identity,  ///< the meshes are already in one frame
        File,      ///< a fit.json written by `glint register` (or any JSON with a 4×4
                   ///< "reference_from_examined" matrix)
        Register,  ///< run the robust registration (coarse + ICP)
        Truth,     ///< a known transform (scenarios with a synthetic pose)
    } mode = Mode::Identity;
    std::filesystem::path fit_file;
    std::string loss = "cauchy";   ///< robust loss: cauchy | huber | tukey | none
    std::string roi;               ///< restrict the fit to a stable region (sphere:/box:)
    bool symmetric = false;
    Rigid truth = Rigid::Identity();
};

struct FitOutcome {
    Rigid reference_from_examined = Rigid::Identity();
    std::string mode;            ///< "identity", "file", "register", "truth"
    std::string json;            ///< the fit's evidence as JSON text (for report.json)
    bool converged = true;
    std::vector<std::string> warnings;
};

/// \throw InputError bad fit file / options; the registration's own errors.
[[nodiscard]] FitOutcome fit_examined(const Mesh& reference, const Mesh& examined, const FitRequest& request);

/// Per reference vertex: signed distance to the (fitted) examined surface along the robust
/// pseudo-normal sign convention, negated so that negative = the examined surface lies inside
/// the reference (loss, dent) and positive = outside (growth, bump).
[[nodiscard]] std::vector<float> signed_distances(const Mesh& reference, const Mesh& fitted_examined);

}  // namespace glint
