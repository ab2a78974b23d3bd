// Fitting the examined mesh into the reference frame, and the per-vertex signed distance
// (shape evidence). One entry point for the command line (sweep, register, calibrate) and
// scenarios: typed options in, the transform and its evidence out.
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "mesh/surface_index.h"
#include "registration/icp.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint {

enum class FitMode {
    Identity,  ///< the meshes are already in one frame
    File,      ///< a fit.json written by `glint register` (any JSON with a 4×4
               ///< "reference_from_examined" matrix)
    Register,  ///< the robust registration (coarse or landmarks/init start, then ICP)
    Truth,     ///< a known transform (scenarios with a synthetic pose)
};
/// "identity" / "file" / "register" / "truth". \throw InputError.
[[nodiscard]] FitMode parse_fit_mode(const std::string& text);
[[nodiscard]] std::string to_string(FitMode mode);

struct FitOptions {
    FitMode mode = FitMode::Identity;
    std::filesystem::path fit_file;  ///< File
    /// Register: loss, samples, iterations, symmetric, coarse, ROI (a mask ROI is read by
    /// fit_examined from its file), seed, … (registration/icp.h).
    RegistrationOptions registration;
    std::filesystem::path landmarks_file;  ///< Register: start from landmark pairs (JSON)
    std::filesystem::path init_file;       ///< Register: start from this fit.json
    Rigid truth = Rigid::Identity();       ///< Truth
    double truth_scale = 1.0;              ///< Truth: the examined surface's true scale

    /// Checks the options without reading any file. \throw InputError naming the field.
    void validate() const;
};

struct FitOutcome {
    /// reference point = reference_from_examined × (examined_scale × examined point).
    Rigid reference_from_examined = Rigid::Identity();
    double examined_scale = 1.0;  ///< 1 unless a similarity fit (--fit-scale) or a file says so
    FitMode mode = FitMode::Identity;
    std::optional<RegistrationResult> registration;  ///< Register (and Truth, as a stub)
    std::string json;  ///< the fit's evidence as JSON text (fit.json / report.json)
    bool converged = true;
    std::vector<std::string> warnings;
};

/// Fits `examined` onto `reference`: reads the fit file, the landmarks (resolving picked
/// pixels) or the initial pose, and a mask ROI, then registers.
/// \throw InputError bad options or files (naming them); the registration's own errors.
/// `reference_index`: the reference's BVH when the run built it already (mesh/surface_index.h).
[[nodiscard]] FitOutcome fit_examined(
    const Mesh& reference, const Mesh& examined, const FitOptions& options,
    const std::shared_ptr<const SurfaceIndex>& reference_index = nullptr);

/// A rigid fit whose residuals still hold a scale of at least this (relative) and at least
/// kScaleTrendSignificance standard errors is warned about, suggesting a similarity fit.
/// note: 0.2 % is 0.1 mm over a 50 mm jaw, the size of the damage the method is after; the
/// scanners of one site are calibrated within 0.1 % (the unchanged real pairs: see
/// docs/evaluation.md).
inline constexpr double kScaleTrendWarning = 0.002;
inline constexpr double kScaleTrendSignificance = 4.0;

/// Brings the examined surface to the fit's scale (positions, voxel axes and field of view ×
/// fit.examined_scale about the origin; nothing to do at 1), then into the reference frame.
void apply_fit(Mesh& examined, const FitOutcome& fit);

/// The shape evidence the decision reads, per reference vertex.
///
/// Tessellation tolerance: two piecewise-flat tessellations of one surface lie apart by up to
/// about h·θ, where h is the local edge length and θ the local turn of the surface across an
/// edge. Smooth parts give the sagitta (≈ h·θ/8 across a chord); sharp parts — a cusp, a
/// ridge, a cone tip whose vertex the other mesh does not share — give much more, because the
/// other mesh cuts the corner. Measured on the real jaw remeshed at 0.5× (vertices on the
/// surface): the distance of every reference vertex to the remesh stayed below 0.92·h·θ with
/// h the remesh's median edge, and half of h·θ with h the longest edge at the examined
/// triangle's corners left no excess above the shape floor on the clean jaw and molar pairs.
/// The distance is measured to the curved surface the examined triangle stands for (Phong
/// tessellation from its corner normals), not to the flat chord: on the clean pairs (jaw at
/// 0.5× and 1.2×, both molars) |d|/(½·h·θ) then stays below 0.94 (0.999-quantile 0.6) where the
/// flat distance reached 1.2 (0.999-quantile 0.9); a third less would leave false regions on
/// the 1.2× jaw.
/// A reference vertex's tolerance is kTessellationTolerance·h·θ with h the longest edge at the
/// corners of the examined triangle its closest point lies on, and θ the largest angle between
/// a vertex normal and an adjacent face normal at the reference vertex or at those corners.
inline constexpr double kTessellationTolerance = 0.5;

struct ShapeEvidence {
    std::vector<float> distance;   ///< signed distance, mesh units (negative = loss)
    std::vector<float> tolerance;  ///< tessellation tolerance, mesh units (see above)
    std::vector<std::uint8_t>
        at_border;  ///< 1: the closest examined point lies on its border (a hole, a cut)
    /// 1: the examined triangle of the closest point faces away from the reference's normal
    /// (more than 90° apart): another sheet of the surface (the scanned side of a thin ear
    /// whose far side the scan never saw), not the examined counterpart of the vertex.
    std::vector<std::uint8_t> facing_away;
};

/// \pre both meshes have vertex normals (loaded meshes do).
/// `examined_index`: the fitted examined mesh's BVH when the run built it already.
[[nodiscard]] ShapeEvidence measure_shape(
    const Mesh& reference, const Mesh& fitted_examined,
    const std::shared_ptr<const SurfaceIndex>& examined_index = nullptr);

}  // namespace glint
