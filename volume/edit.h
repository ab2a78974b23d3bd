// A known change applied to a volume, to make longitudinal pairs with exact ground truth: the
// object moved by a rigid motion and locally eroded (values lowered inside a ball), resampled
// on the same grid.
#pragma once

#include "mesh/geometry.h"
#include "volume/acquisition.h"
#include "volume/volume.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace glint {

/// Values inside a ball lowered to `value` (never raised), in the original object's frame.
struct Erosion {
    Vec3d center{0, 0, 0};  ///< physical, mm (before the motion)
    double radius = 1.0;    ///< mm
    float value = 0.0f;     ///< what the eroded material becomes (CT soft tissue, air, …)
};

struct VolumeEdit {
    /// Where a point of the object goes: p_new = moved_from_original · p (physical mm).
    Rigid moved_from_original = Rigid::Identity();
    std::vector<Erosion> erosions;
    /// Another acquisition's voxel size (mm along i, j, k); unset: the input's grid. The output
    /// grid keeps the input's origin and direction and covers its extent (cropped to what the
    /// input saw of the moved object, edit_volume); each output voxel is
    /// the mean of 2 × 2 × 2 samples spread over its own extent (the scanner integrates over
    /// its voxel: partial volume at the new size).
    std::optional<Vec3d> spacing;
    /// Gaussian noise added to every output voxel, σ in the volume's values (0: none), drawn
    /// from `noise_seed`: an acquisition's own noise realisation.
    double noise_sigma = 0.0;
    std::uint32_t noise_seed = 1;
    /// The acquisition's point-spread blur (FWHM, mm) and the noise's correlation length (mm),
    /// volume/acquisition.h; 0: none, white noise.
    double psf_fwhm = 0.0;
    double noise_correlation = 0.0;
};

/// \throw InputError naming `who` and the erosion (1-based) whose centre, radius or value is
/// not finite, or whose radius is not > 0.
void check_erosions(std::span<const Erosion> erosions, const std::string& who);

/// `value` at the object's point `p` (original frame) after `erosions`: each ball lowers it
/// towards its value with a weight that falls linearly from 1 to 0 over `ramp` mm across the
/// ball's surface (partial volume), value ← value + w · (min(value, target) − value).
[[nodiscard]] float eroded_value(float value, const Vec3d& p, std::span<const Erosion> erosions,
                                 double ramp);

/// The motion "rx,ry,rz,tx,ty,tz" (degrees, mm; mesh/damage.h parse_pose_spec) about a pivot:
/// p' = R (p - pivot) + pivot + t.
[[nodiscard]] Rigid motion_about(const Rigid& pose, const Vec3d& pivot);

/// The edited volume on the input's grid (or the grid of `edit.spacing`): each output voxel at
/// x takes the eroded input at p = moved_from_original⁻¹ · x (trilinear). The grid is cropped
/// to the input's field of view: a motion takes part of the object out of what the input saw,
/// and a scan of the moved object has no data there, so the output keeps only whole voxels
/// whose every sample lies inside the input (its surface ends open at the cut, as a scan's
/// does at its field of view; the two fields of view differ by the motion).
/// \throw InputError a voxel size that is no size or over the budget; a motion that leaves
/// nothing of the input in view.
/// Erosion is partial-volume correct: the weight of a ball falls linearly from 1 to 0 over
/// one voxel (the mean spacing) across its surface (eroded_value). The scanner's blur and noise
/// (psf_fwhm, noise_sigma, noise_correlation) come last (apply_scanner).
[[nodiscard]] Volume edit_volume(const Volume& input, const VolumeEdit& edit);

/// The edit as JSON (motion as a 4×4 matrix, erosion centres before and after the motion,
/// radii, values): the ground truth written beside an edited volume.
[[nodiscard]] std::string edit_json(const VolumeEdit& edit);

}  // namespace glint
