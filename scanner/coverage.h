// Coverage: which reference vertices a zoom level observed, and how much of the asked-for
// surface that is. Unseen vertices are never declared undamaged: they are reported.
//
// A vertex is *seen* at a zoom when some observation passed the coverage rule
// (scanner/backproject.h) and, with an ROI, it lies inside the ROI (outside it nothing is
// analysed). Coverage = seen area / asked area, the asked area being the ROI's vertices' or
// the whole surface's (dual vertex areas).
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "mesh/roi.h"
#include "scanner/atlas.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace glint {

struct Coverage {
    std::vector<std::uint8_t> seen;  ///< per vertex
    double seen_area = 0.0;          ///< mesh units²
    double asked_area = 0.0;         ///< mesh units²
    double fraction = 0.0;           ///< seen / asked (0 when nothing was asked)
};

/// \pre atlas arrays sized as the mesh; a mask ROI already read.
[[nodiscard]] Coverage coverage_of(const Mesh& reference, const ZoomAtlas& atlas,
                                   const std::optional<Roi>& roi);

/// A connected patch of unseen vertices.
struct UnseenPatch {
    std::size_t vertices = 0;
    double area = 0.0;
    Vec3d centroid{0, 0, 0};
};

struct UnseenSummary {
    std::size_t vertices = 0;
    double area = 0.0;
    std::vector<UnseenPatch> patches;  ///< largest first
};

/// Unseen vertices (inside the ROI when there is one) grouped into patches through edges.
[[nodiscard]] UnseenSummary unseen_patches(const Mesh& reference,
                                           const std::vector<std::uint8_t>& seen,
                                           const std::optional<Roi>& roi);

}  // namespace glint
