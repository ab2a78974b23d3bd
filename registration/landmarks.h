// Landmark pairs: a closed-form starting pose from ≥ 3 corresponding points, and the JSON
// file format users write them in (points, or pixels picked in named views; analysis/
// landmarks.h turns picked pixels into points).
#pragma once

#include "mesh/geometry.h"

#include <optional>
#include <string>
#include <vector>

namespace glint {

/// Closed-form rigid fit of point pairs (Umeyama 1991, Eigen::umeyama, no scaling):
/// reference ≈ T · examined. \throw InputError fewer than 3 pairs, collinear points.
[[nodiscard]] Rigid fit_landmarks(const std::vector<Vec3d>& examined,
                                  const std::vector<Vec3d>& reference);

/// A view of one mesh as `glint pick` frames it (an orthographic view around the mesh's
/// bounding sphere; registration/ does not frame views, analysis/landmarks.h resolves them).
struct LandmarkView {
    double azimuth_deg = 0.0;
    double elevation_deg = 0.0;
    int size = 256;          ///< image width = height, pixels
    double footprint = 0.0;  ///< mesh units per pixel; 0 = frame the whole mesh
};

/// One side of a landmark pair: a 3D point, or a pixel (centres at +0.5) picked in a view.
struct LandmarkSide {
    std::optional<Vec3d> point;  ///< set for a 3D point; empty for a picked pixel
    LandmarkView view;
    double u = 0.0;
    double v = 0.0;
};

struct LandmarkPair {
    LandmarkSide examined;
    LandmarkSide reference;
};

/// Reads landmark pairs: JSON {"pairs": [{"examined": SIDE, "reference": SIDE}, …]} where a
/// SIDE is [x, y, z] or {"view": {"azimuth": A, "elevation": E, "size": N, "footprint": F
/// (optional)}, "pixel": [u, v]}.
/// \throw IoError cannot open; InputError naming the file, the pair and the side for a
/// wrong type or shape.
[[nodiscard]] std::vector<LandmarkPair> read_landmarks(const std::string& path);

}  // namespace glint
