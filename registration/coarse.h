// Coarse alignment: a starting pose for ICP when the examined mesh may be far from its place.
//
// Hypotheses: the identity (trust the scan's placement) and the two meshes' principal frames
// (centroid + axes of the sample covariance) matched under each of the four proper sign
// flips. Each is refined by a short robust ICP on a few samples and scored by its robust
// residual spread, penalised by the share of the surface that matched. A symmetric shape
// scores several hypotheses about equally; then the one that turns the examined mesh least
// is kept, and the description says so. When the kept hypothesis lays under 90 % of the
// examined surface on the reference (a partial scan, whose principal axes are not the
// whole's), poses over all orientations are tried too (registration/detail/rotation_search.h).
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "registration/icp.h"

#include <string>
#include <vector>

namespace glint {

/// One scored hypothesis (after its short ICP).
struct CoarseHypothesis {
    Rigid reference_from_examined = Rigid::Identity();
    std::string name;    ///< "identity", "principal axes, signs (1, -1, -1)", …
    double score = 0.0;  ///< robust residual / matched share²: lower is better
};

struct CoarseAlignment {
    Rigid reference_from_examined = Rigid::Identity();
    /// The hypothesis kept, with a note when several fit about equally (symmetric shape).
    std::string description;
    std::vector<CoarseHypothesis> hypotheses;
};

/// Scores every hypothesis and keeps the best (see file comment). Uses options.samples
/// (capped at 2000), seed, loss and ROI. \throw InputError invalid options or empty meshes.
[[nodiscard]] CoarseAlignment coarse_align(const Mesh& reference, const Mesh& examined,
                                           const RegistrationOptions& options = {});

}  // namespace glint
