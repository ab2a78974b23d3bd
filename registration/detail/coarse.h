// coarse_align over indexes and samples register_meshes already built. Internal.
#pragma once

#include "registration/closest_point.h"
#include "registration/coarse.h"
#include "registration/detail/icp_core.h"

#include <vector>

namespace glint::detail {

/// See glint::coarse_align; `examined` with vertex normals, `samples` the examined samples of
/// the fine fit.
[[nodiscard]] CoarseAlignment coarse_align(const ClosestPointIndex& reference, const Mesh& examined,
                                           const std::vector<Sample>& samples,
                                           const RegistrationOptions& options, double diagonal);

}  // namespace glint::detail
