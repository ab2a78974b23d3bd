// Rigid registration of an examined mesh onto a reference mesh.
//
//   coarse (optional): centroid + principal axes, every proper sign hypothesis and the
//                      identity, each scored after a short robust ICP; when the kept one
//                      lays under 90 % of the examined surface on the reference (a partial
//                      scan), a rotation search over all orientations; or landmarks
//   fine:             point-to-plane ICP, 6 DoF (angle-axis + translation), solved with
//                     Ceres under a robust loss whose scale comes from the residuals' MAD
//                     and is annealed from wide to tight; pairs whose normals disagree are
//                     rejected; samples are drawn area-uniformly on the examined mesh
//                     (Chen & Medioni 1992 point-to-plane; robust M-estimation as in
//                     Open3D's RobustKernel).
// Coarse alignment lives in registration/coarse.h, landmarks in registration/landmarks.h,
// fit.json reading and writing in registration/fit_io.h.
// Damage must not pull the fit: a robust loss down-weights the damaged area, an ROI can
// restrict the fit to a stable region.
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "mesh/roi.h"
#include "mesh/surface_index.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint {

enum class RobustLoss { None, Huber, Cauchy, Tukey };

/// "none" / "huber" / "cauchy" / "tukey". \throw InputError.
[[nodiscard]] RobustLoss parse_loss(const std::string& text);
[[nodiscard]] std::string to_string(RobustLoss loss);

struct RegistrationOptions {
    RobustLoss loss = RobustLoss::Cauchy;
    /// Loss scale = anneal factor × 1.4826 × MAD of the residuals; the factor goes from
    /// `anneal_start` down to `anneal_end` (halving each iteration).
    double anneal_start = 8.0;
    double anneal_end = 2.0;
    int samples = 20000;  ///< area-uniform samples on the examined mesh
    int max_iterations = 60;
    int inner_iterations = 8;            ///< Ceres LM iterations per ICP iteration
    double max_normal_angle_deg = 60.0;  ///< reject pairs whose normals differ more
    /// Convergence on parameter change: rotation change below this (degrees) and
    /// translation change below `translation_tolerance` × the larger bounding diagonal.
    double rotation_tolerance_deg = 1e-7;
    double translation_tolerance = 1e-9;
    /// Convergence on cost: once the loss scale is fully annealed, the relative change of the
    /// robust cost between two consecutive iterations is below this. note: 1e-6 is a
    /// conventional choice, not a tuned one; on the phantom and bunny pairs the matching
    /// reaches a fixed point (step and cost change exactly 0) first.
    double cost_tolerance = 1e-6;
    /// A fit whose overlap (see RegistrationResult) is below this is not converged
    /// ("low overlap"). note: 0.2 lies well below the partial overlap of real range scans
    /// 45° apart (Stanford bunny pairs: 0.66 to 0.91) and above what a fit of unrelated
    /// surfaces reaches.
    double min_overlap = 0.2;
    /// A sample overlaps the reference when, at the final pose, its closest reference point
    /// lies within this × the larger bounding diagonal, inside the ROI, with a compatible
    /// normal. note: 1% of the size is ~15× the RMS of real scans (bunny: 0.12 to 0.15 mm
    /// on ~0.2 m) and below the misfit of unrelated surfaces.
    double overlap_distance = 0.01;
    bool coarse = true;      ///< try principal-axis hypotheses first (not with landmarks/init)
    bool symmetric = false;  ///< also pull reference samples onto the examined mesh
    /// A similarity fit: the fine fit also estimates one scale factor of the examined surface
    /// (scanners calibrated apart, a mesh in other units). Off: the fit is rigid, and the
    /// scale a similarity would still add is measured and reported (scale_trend).
    bool fit_scale = false;
    /// The examined surface's scale to start from (multiplies its positions before anything
    /// else; with fit_scale the fit refines it). 1: none.
    double initial_scale = 1.0;
    /// Measure scale_trend and the scale's uncertainty at the end (one pass over the pairs and
    /// nine 7×7 solves, 2 % of a 200k-triangle fit; off for fits where a scale means nothing,
    /// as a surface against its own mirror image).
    bool measure_scale = true;
    /// Fit only on this region of the reference (a stable region, mesh/roi.h); a vertex
    /// mask must already be read (Roi::needs_mask() false). Empty: the whole surface.
    std::optional<Roi> roi;
    std::optional<Rigid> initial;  ///< start from this reference_from_examined
    std::uint32_t seed = 1;        ///< sampling is deterministic for a seed

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

struct IcpIteration {
    int iteration = 0;
    double cost = 0.0;        ///< robust cost ½Σρ(r²) after this iteration's solve
    double rms = 0.0;         ///< of inlier point-to-plane residuals before the step
    double loss_scale = 0.0;  ///< 0 without a robust loss
    double overlap = 0.0;     ///< share of samples with an accepted pair
    double rotation_step_deg = 0.0;
    double translation_step = 0.0;
    double scale_step = 0.0;  ///< |ln| of the step's scale (similarity fit; 0 when rigid)
};

struct RegistrationResult {
    Rigid reference_from_examined = Rigid::Identity();
    Rigid examined_from_reference = Rigid::Identity();
    // Evidence, all measured at the final pose. A sample has an accepted pair when its
    // closest reference point lies within `overlap_distance` × size, inside the ROI, with a
    // compatible normal; samples whose closest point lies outside the ROI are left out.
    double rms = 0.0;              ///< point-to-plane RMS of inliers (mesh units)
    double inlier_fraction = 0.0;  ///< share of accepted pairs within 3σ (σ = 1.4826 MAD)
    double overlap = 0.0;          ///< share of samples with an accepted pair
    int iterations = 0;
    bool converged = false;
    /// Why ICP stopped: "parameter change", "cost change" (both converged), "max
    /// iterations", "low overlap", "no overlap", "solver failure".
    std::string termination;
    std::string termination_detail;  ///< one line with the numbers behind `termination`
    std::string coarse;              ///< which coarse hypothesis was kept
    /// The fitted motion is a similarity: reference point = reference_from_examined ×
    /// (examined_scale × examined point); examined_from_reference is the inverse of the
    /// rigid part alone (it maps onto the scaled examined surface). 1 for a rigid fit.
    double examined_scale = 1.0;
    /// One standard error of examined_scale (0 for a rigid fit): the jackknife over the
    /// surface's eight octants about its centre, so that spatially correlated residuals
    /// (noise, damage) widen it as they should; see docs/method.md.
    double scale_uncertainty = 0.0;
    /// At the final pose, the relative scale one similarity step would still add (−0.01: the
    /// examined surface stands 1 % too large), with its jackknife standard error: the radial
    /// trend of the signed distance that a rigid fit between scanners of different
    /// calibration leaves. About 0 after a similarity fit.
    double scale_trend = 0.0;
    double scale_trend_uncertainty = 0.0;
    /// The reference's samples were matched on the examined surface: the examined surface
    /// covers more than 1.5× the reference's area and the fit the usual way round found too
    /// little overlap. The evidence above is measured the turned way round.
    bool reference_on_examined = false;
    std::vector<IcpIteration> log;
};

/// Registers `examined` onto `reference`. An honest "did not converge" is a result, not an
/// error. `reference_index`: the reference's BVH when the run built it already (shared with
/// the sweep and the pictures, mesh/surface_index.h); null: one is built.
/// \throw InputError invalid options, an ROI with no reference surface inside.
[[nodiscard]] RegistrationResult register_meshes(
    const Mesh& reference, const Mesh& examined, const RegistrationOptions& options = {},
    const std::shared_ptr<const SurfaceIndex>& reference_index = nullptr);

}  // namespace glint
