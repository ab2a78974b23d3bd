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
#pragma once

#include "scenario/detail/toml_reader.h"
#include "scenario/scenario.h"

namespace glint::detail {

/// The keys above, when given. `volume`: the pair's reference is a volume (they need one).
/// \throw InputError (through `r`) for a negative σ, a voxel size ≤ 0 or no volume.
[[nodiscard]] Acquisition read_acquisition(TableReader& r, bool volume);

/// The scan `acquisition` makes of `volume` moved by `edit` (its motion and erosions), or the
/// volume itself when nothing is asked.
[[nodiscard]] Volume acquire(const Volume& volume, VolumeEdit edit, const Acquisition& acquisition);

/// One line for a scenario's notes: "σ 20 (seed 3), voxels 0.8 × 0.8 × 0.8 mm" or "as stored".
[[nodiscard]] std::string describe(const Acquisition& acquisition);

}  // namespace glint::detail
