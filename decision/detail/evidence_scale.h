// The evidence at a smoothing scale (decision/decision.h, "Floors that stay honest"): where the
// floors measured at the vertices' own scale are implausible (rough surfaces: CT staircase and
// partial-volume noise), the shape evidence is read over a neighbourhood of radius r instead,
// where noise averages out and a change at least that wide keeps its depth. Internal to
// decision/decision.cpp.
#pragma once

#include "decision/decision.h"
#include "mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace glint::detail {

/// The shape evidence over radius r around each vertex: a weighted plane fit of the signed
/// distance in the vertex's tangent plane over the connected part of the mesh within r
/// (Gaussian weights, σ = r/2; seen vertices with an examined surface only).
struct ScaledEvidence {
    double radius = 0.0;
    std::vector<float> distance;   ///< the fit's value at the vertex (mesh units)
    std::vector<float> tolerance;  ///< tessellation tolerance, averaged the same way
    /// The fit's slope as an angle (degrees): the tilt of the examined surface against the
    /// reference over r, the normal evidence at this scale.
    std::vector<float> tilt_deg;
};

/// \pre evidence.distance holds one value per reference vertex; reference has normals.
/// `stride` > 1 fits every stride-th vertex only and leaves the others NaN (robust statistics
/// of the evidence at a wide radius at a fraction of the cost: decision.cpp detection_limit).
[[nodiscard]] ScaledEvidence scaled_evidence(const Mesh& reference,
                                             const DecisionEvidence& evidence, double radius,
                                             std::size_t stride = 1);

/// The same evidence over a wide radius at a fraction of the cost: one vertex is fitted per
/// cell of a quarter of the radius (σ/2) and per facing (the normal's dominant axis and sign,
/// so both sides of a thin plate are read), and every other vertex takes the plane fitted at
/// the nearest fitted one through mesh edges, evaluated where it stands (its tilt and tolerance
/// as they are). Over a disc of radius r the fit changes little within σ/2, so the field it
/// gives is the full reading's at that scale; the cost is about
/// 16π fits' worth of neighbours per vertex whatever the radius (decision.cpp search_wider).
/// \pre as scaled_evidence.
[[nodiscard]] ScaledEvidence sparse_scaled_evidence(const Mesh& reference,
                                                    const DecisionEvidence& evidence,
                                                    double radius);

/// The radii tried, smallest first: 2, 4, 8, 16 and 32 median edge lengths of the reference,
/// at most 8 % of the size.
[[nodiscard]] std::vector<double> scale_ladder(const Mesh& reference, double size);

}  // namespace glint::detail
