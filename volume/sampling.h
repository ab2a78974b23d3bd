// Reading a volume between its voxels.
#pragma once

#include "volume/volume.h"

namespace glint {

/// Trilinear interpolation at a fractional index (i, j, k); within the outer voxels' own half
/// (the field of view the grid covers) the nearest inner value; `outside` beyond.
[[nodiscard]] float sample_trilinear(const Volume& v, const Vec3d& index, float outside);

}  // namespace glint
