// Landmarks given as picked pixels: a pixel of a named view of a mesh becomes the surface
// point it shows, with the framing and picking of `glint pick` (render/ frames the view,
// registration/ casts the ray; analysis/ may use both).
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "registration/closest_point.h"
#include "registration/landmarks.h"
#include "render/view.h"

#include <string>
#include <vector>

namespace glint {

/// The orthographic view `glint pick` uses: around the mesh's framing sphere, width =
/// height = size, zoom = the footprint when given, else the whole mesh framed.
/// \throw InputError invalid view (see ViewSpec::validate).
[[nodiscard]] View pick_view(const Mesh& mesh, const LandmarkView& view);

/// Landmark pairs as 3D points: points are kept, pixels are picked on their mesh (the
/// examined side on `examined`, the reference side on `reference`).
struct ResolvedLandmarks {
    std::vector<Vec3d> examined;
    std::vector<Vec3d> reference;
};

/// \throw InputError naming `source`, the pair and the side when a pixel shows no surface.
[[nodiscard]] ResolvedLandmarks resolve_landmarks(const std::vector<LandmarkPair>& pairs,
                                                  const ClosestPointIndex& reference,
                                                  const ClosestPointIndex& examined,
                                                  const std::string& source);

}  // namespace glint
