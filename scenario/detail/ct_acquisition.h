// How each scan of a CT pair was acquired (issue 24, the real-pair generator): a volume
// reference's two scans are made from the one noiseless volume, each with its own noise
// realisation and, when given, its own voxel size; the ground truth comes from the noiseless
// volume (volume/edit.h does the resampling, the partial volume and the noise).
//
//   [reference] / [examined]
//   volume_noise = 20.0          # σ of Gaussian noise per voxel, in the volume's values
//   volume_noise_seed = 3        # the realisation (give the two scans different seeds)
//   voxel_size = [0.8, 0.8, 0.8] # mm: resampled over the same extent, each voxel the mean
//                                # over its own extent
//   psf_fwhm = 0.6               # mm: the scanner's Gaussian blur (volume/acquisition.h)
//   noise_correlation = 0.3      # mm: the noise correlated as a cone-beam reconstruction makes it
//
// A mesh scanned as CT ([reference] scan_as_ct = true) needs the reference's voxel_size; the
// examined scan takes each key it does not give from the reference, and a noise seed one above
// the reference's (an independent realisation).
#pragma once

#include "scenario/detail/toml_reader.h"
#include "scenario/scenario.h"

namespace glint::detail {

/// The keys above, when given, over `inherit` (seed + 1) or the defaults. `volume`: the pair's
/// reference is a volume or a mesh scanned as CT (they need one).
/// \throw InputError (through `r`) for a negative σ, width or correlation, a voxel size ≤ 0 or
/// no volume.
[[nodiscard]] Acquisition read_acquisition(TableReader& r, bool volume,
                                           const Acquisition* inherit = nullptr);

/// What a reference scanned as CT hands its examined scan when [examined] says nothing.
[[nodiscard]] Acquisition inherited(const Acquisition& reference);

/// The scan `acquisition` makes of `volume` moved by `edit` (its motion and erosions), or the
/// volume itself when nothing is asked. `noiseless`: the same scan before its noise (which
/// apply_scanner adds last), for the pair's truth.
[[nodiscard]] Volume acquire(const Volume& volume, VolumeEdit edit, const Acquisition& acquisition,
                             bool noiseless = false);

/// The scan `acquisition` makes of the solid `object` bounds (scenario/ct_of_mesh.h), moved by
/// `edit`'s motion with its erosions; its values `background` outside, `inside` within.
[[nodiscard]] Volume acquire(const Mesh& object, const VolumeEdit& edit,
                             const Acquisition& acquisition, float background, float inside,
                             bool noiseless = false);

/// One line for a scenario's notes: "noise σ 20 (seed 3), voxels 0.8 × 0.8 × 0.8 mm" or
/// "as stored".
[[nodiscard]] std::string describe(const Acquisition& acquisition);

}  // namespace glint::detail
