// Left–right asymmetry of one surface (issue 27): the surface compared with its own mirror image
// through the regular pipeline (analysis/analysis.h).
//
//   surface ─▶ symmetry plane (registration/symmetry_plane.h) ─▶ plausible? ── no ─▶ verdict
//                         │ yes
//   reference = the surface, examined = its reflection about the plane (already in place:
//   the fit stays the identity) ─▶ analyse() ─▶ regions
//                         │
//   pair_findings: a one-sided change shows twice, at its place and at its mirror image, with
//   opposite signs; each pair is one finding, shown on the side whose surface bends less evenly
//   there (the changed side, on a smooth surface), else on the side that has less; the other
//   member is named as its mirror. A region whose mirror image made no region of its own (the
//   change's crater lies near other mirrored structures) is weighed the same way against the
//   surface at its mirror image, and may be shown there. One scan cannot prove which side
//   changed (a dent on one side is the same asymmetry as a bump on the other), only that the
//   sides differ.
//
// Signs: the asymmetry field is the surface minus the mirror of the other side, along the
// outward normal (negative: this side lies inside the mirrored other side, "less").
#pragma once

#include "analysis/analysis.h"
#include "registration/symmetry_plane.h"

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace glint {

/// The one sentence every asymmetry result carries (report.json, terminal).
inline constexpr std::string_view kOneScanCaveat =
    "one scan cannot tell which side changed, only that the two sides differ";

struct AsymmetryOptions {
    SymmetryPlaneOptions plane;                ///< the plane's fit (--fit-roi, loss, samples)
    std::optional<SymmetryPlane> given_plane;  ///< --plane: checked, not fitted
    /// \throw InputError naming the field.
    void validate() const { plane.validate(); }
};

/// The plane, and the mirror the pipeline compares the surface with.
struct AsymmetryPlane {
    SymmetryPlaneResult plane;
    Mesh mirror;  ///< the surface reflected about the plane (empty when not plausible)
};

/// Estimates (or checks the given) plane and, when it is plausible, makes the mirror.
/// \throw InputError invalid options, an empty mesh.
[[nodiscard]] AsymmetryPlane prepare_asymmetry(const Mesh& mesh, const AsymmetryOptions& options);

/// One asymmetry: a pair of regions (or a lone region) reported once.
struct AsymmetryFinding {
    /// The region reported, 1-based: on the finding's side, or (at_mirror_image) its mirror
    /// image on the other side.
    std::int32_t region = 0;
    std::int32_t mirror_region = 0;  ///< the region at its mirror image, 0 when none was found
    Vec3d side{0, 0, 0};             ///< unit: the plane's normal towards the region's side
    double depth = 0.0;              ///< this side minus the mirrored other side, peak (mesh units)
    double area = 0.0;               ///< mesh units²
    double volume = 0.0;  ///< this side minus the mirrored other, mesh units³ (neg = less)
    Vec3d centroid{0, 0, 0};
    /// The mirror has no surface there (the other side is missing or outside the scan): no
    /// depth or volume (NaN), "no mirrored surface" in words.
    bool mirror_missing = false;
    /// How irregularly the surface bends over this region and over its mirror-image region
    /// (spread of the umbrella curvature, 1/mesh units); `side_by_shape`: the side was chosen
    /// as the less even one (see pair_findings).
    double roughness = 0.0;
    double mirror_roughness = 0.0;
    bool side_by_shape = false;
    /// A lone region shown at its mirror image: the finding's side, centroid, depth and volume
    /// are the mirror image's (this side against the mirrored other), and `region` lies on the
    /// other side. mirror_roughness is then the region's own, roughness the surface's at its
    /// mirror image (the mirrored region's vertices' nearest surface vertices).
    bool at_mirror_image = false;
};

/// A pair is shown on the side whose surface bends less evenly over its region when that
/// spread exceeds the other side's by this factor.
/// note: on the jaw's right condyle (0.4 mm deep, 2.5–3 mm radius, re-tessellated jaw) the
/// changed side's spread over its mirror's is 1.31 for a dent, 1.83 for a bump and 2.0 for a
/// flattening; 1.2 keeps all three, the dent with a thin margin (below it the fallback, the
/// side with less, still names a loss's side right; a bump's would then be named as less on
/// the other side).
inline constexpr double kRoughnessRatio = 1.2;

/// How symmetric the surface is outside the findings: |asymmetry field| of the vertices in no
/// region (mesh units).
struct SymmetryFloor {
    double rms = 0.0;
    double p95 = 0.0;
    double max = 0.0;
    /// The smallest one-sided change the decision can tell from that asymmetry (its evidence
    /// scale, decision.h EvidenceScale): deeper than this, over at least this area (mesh
    /// units, units²; NaN: not stated).
    double min_depth = std::numeric_limits<double>::quiet_NaN();
    double min_area = std::numeric_limits<double>::quiet_NaN();
};

struct AsymmetryFindings {
    std::vector<AsymmetryFinding> findings;
    SymmetryFloor floor;
    std::vector<float> field;  ///< per vertex: the asymmetry field (see file comment)
};

/// Pairs the regions of one zoom's decision (`mesh`, with normals, analysed against its mirror).
/// A region's partner is the unpaired region of the opposite sign whose centroid lies nearest
/// the mirror image of its centroid, within twice the larger region's radius (√(area/π)). The
/// pair is shown on the side where the surface bends less evenly (a change on a smooth surface
/// turns its curvature over; its intact mirror image does not), when clearly so
/// (kRoughnessRatio); else on the side that has less. A dent or bump without a partner is weighed
/// the same way against the surface at its mirror image (the vertices nearest its mirrored
/// vertices): shown there (at_mirror_image) when that side bends less evenly, or, neither clearly
/// so, when the region's own side has more. Either way one scan cannot prove which side
/// changed: the choice is a reading of the shape, said so in the report.
[[nodiscard]] AsymmetryFindings pair_findings(const Mesh& mesh, const SymmetryPlane& plane,
                                              const AnalysisResult& result, std::size_t zoom = 0);

/// The result of the surface analysed against its mirror, turned to say this side against the
/// mirrored other side (the findings' terms): the signed distance, each region's depths and
/// volume negated (and the sign in their evidence sentence), dents and bumps swapped (a dent:
/// this side has less). Missing surface stays, and a hole of the mirror has no depth (its
/// hole_depth unknown, no hole a loss: decided_shape paints no value there).
/// \pre not yet turned (pair_findings reads the result as analyse() made it).
void as_side_against_mirror(AnalysisResult& result);

/// "0.42 mm less than the mirrored right, area 12.3 mm², volume 1.23 mm³" for a finding on a
/// side named `side_name`, the other side named `other_name` (e.g. from report/orientation.h).
[[nodiscard]] std::string describe(const AsymmetryFinding& finding, const std::string& side_name,
                                   const std::string& other_name, const std::string& unit);

}  // namespace glint
