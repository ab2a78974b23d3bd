// Checks of volume headers glint makes before ITK reads them (no ITK here): the direction
// matrix and geometry numbers a scanner can hold, the NIfTI header, the MetaImage header. Each
// refusal is one InputError line naming the file (volume/detail/itk_io.cpp uses them).
#pragma once

#include <array>
#include <filesystem>

namespace glint::detail {

/// A direction matrix, m[row][column], the columns the axes (plain arrays: itk_io.cpp sees
/// ITK's bundled Eigen, not ours).
using Matrix3 = std::array<std::array<double, 3>, 3>;

/// Refuses a direction matrix that is not finite or whose axes do not span 3D.
void check_direction(const Matrix3& m, const std::filesystem::path& path);

/// A number a scanner's geometry can hold: finite, at most `limit` in magnitude, zero or a
/// normal float.
[[nodiscard]] bool plausible(double x, double limit);

// note: 1e6 mm for a voxel axis (a kilometre) and 1e9 mm for a position bound what any scan
// holds; far beyond them ITK's matrix code overflows.
inline constexpr double kMaxAxisMm = 1e6;
inline constexpr double kMaxPositionMm = 1e9;

/// What ITK would trip over in a NIfTI header (.nii, .nii.gz), checked before it reads it.
void check_nifti_header(const std::filesystem::path& path);

/// A MetaImage header read up to ElementDataFile and refused where MetaIO would misbehave.
void check_metaimage_header(const std::filesystem::path& path);

}  // namespace glint::detail
