// What a CT scanner adds to the object it images (issue 50, item 6: CBCT-class pairs): the
// blur of its point-spread function and its noise, which in cone-beam CT is correlated over
// neighbouring voxels (the reconstruction filter spreads each projection's noise). Both act on
// a volume already sampled at the scan's voxel size (partial volume: each voxel the mean of the
// object over its extent), in this order: the optics blur, then the detector adds noise.
#pragma once

#include "volume/volume.h"

#include <cstdint>

namespace glint {

struct ScannerModel {
    /// Full width at half maximum of the Gaussian point-spread function, mm (0: none).
    double psf_fwhm = 0.0;
    /// σ of the noise per voxel, in the volume's values (0: none).
    double noise_sigma = 0.0;
    /// The noise's correlation: white noise smoothed by a Gaussian of this σ in mm, then scaled
    /// back to `noise_sigma` per voxel (0: white, independent voxels). Two voxels d apart then
    /// correlate by exp(−d² / (4 · correlation²)).
    double noise_correlation = 0.0;
    std::uint32_t noise_seed = 1;  ///< the realisation
    [[nodiscard]] bool any() const { return psf_fwhm > 0 || noise_sigma > 0; }
};

/// σ of a Gaussian from its full width at half maximum: FWHM / (2 √(2 ln 2)).
[[nodiscard]] double gaussian_sigma_from_fwhm(double fwhm);

/// Smooths `volume` in place with a Gaussian of σ `sigma_mm` along every physical axis (one
/// separable pass per grid axis, σ in that axis's voxels; the kernel is cut at 3σ and the
/// volume's outer values repeat beyond its edge, so a uniform volume stays uniform). A σ below
/// a hundredth of a voxel leaves the axis alone.
void gaussian_smooth(Volume& volume, double sigma_mm);

/// \throw InputError a negative or non-finite width, σ or correlation (what apply_scanner
/// checks first; callers that work long before it may check early).
void check_scanner(const ScannerModel& scanner);

/// The scanner's blur and noise added to `volume` in place (see ScannerModel). White noise is
/// drawn voxel by voxel in storage order from `noise_seed` (the same values as a plain loop).
/// \throw InputError a negative or non-finite width, σ or correlation.
void apply_scanner(Volume& volume, const ScannerModel& scanner);

}  // namespace glint
