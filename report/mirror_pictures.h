// What the outputs of a run that compares a surface with its own mirror image (glint
// asymmetry, analysis/asymmetry.h) add: the symmetry plane drawn on atlas.png, and the words
// of the finding (this side against the mirrored other side) in the legends and close-ups.
#pragma once

#include "mesh/mesh.h"

#include <string>

namespace glint {

/// The plane the examined surface (the mirror) was made about, with the fit's evidence.
struct MirrorPictures {
    Vec3d normal{1, 0, 0};  ///< unit
    double offset = 0.0;    ///< the plane: normal · p = offset (mesh units)
    double residual = 0.0;  ///< RMS of the mirrored surface against the surface (mesh units)
    /// Signed distance of `p` from the plane (positive on the normal's side).
    [[nodiscard]] double distance(const Vec3d& p) const { return normal.dot(p) - offset; }
};

}  // namespace glint
