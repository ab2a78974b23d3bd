// What both surfaces can compare (issue 24). A reference vertex is compared only where both
// surfaces hold surface around it; elsewhere it is *not compared*: reported as coverage, left
// out of the noise floors, and never the seat of a dent, a bump or a missing-surface region.
//
// The rule, per reference vertex (ℓ = the reference's median edge length):
//   gone         the examined surface is absent there: most views found no examined surface
//                behind the seen vertex (the sweep's per-view hits, ZoomAtlas::missing), or its
//                closest examined point lies more than ℓ/2 away on a border of the examined
//                mesh (a partial scan, a cut, a hole) or on a triangle facing away from the
//                vertex's normal (another sheet). Gone vertices are grouped through edges.
//   hole         a gone group that lies away from the reference's own borders (at most a
//                quarter of its area within one edge of them, no run of them as long as
//                half its rim on reached surface unless it is a cap: kMaxOpenRim,
//                kMinCapCoherence) and covers at most kMaxHoleShare
//                of the reference's area (kMaxLossShare where the examined surface encloses
//                its solid, `encloses`: it holds surface wherever the object has some, so
//                what it lacks is gone, however large: a segmental resection): the examined
//                scan covered the surface around it, so the surface is really gone there (a
//                resection, worn-away material, or a scanner's dropout). It stays compared;
//                its kind follows the shape (below), surface gone (a dent in a hole) is listed
//                first among the regions, its volume the solid it bounds with its rim.
//   beyond view  a gone group holding a vertex that the examined scan's field of view does not
//                hold (within a voxel of its cut, or beyond it: mesh/field_of_view.h; known for
//                surfaces extracted from volumes): the scan had no data there, so its surface
//                ends open at its own cut whatever the reference does. Not reached, never a
//                hole, whatever the surface around it (a field of view through a skull's dome
//                leaves the dome's top with reached surface all round it).
//   dropout      a gone group that would be a hole, on a one-view examined scan (a range
//                image: mesh/scan_view.h), whose reference surface faces that scan's sensor at
//                more than kGrazingDeg for most of its area: the sensor saw it only at grazing
//                incidence, where range scanners drop out. Not reached, not a hole.
//   not reached  every other gone group: the examined scan did not cover it.
//   reference border  within kBandEdges·ℓ (along the reference's edges) of a border edge of
//                the reference: a field-of-view cut, a scan's edge, a crop.
//   examined border   within kBandEdges·ℓ of a not-reached vertex: the examined surface's
//                open border mapped onto the reference through the fit.
//   below resolution  another sheet of either surface lies closer along the vertex's normal
//                than a voxel of the scans' grids (a thin plate, a narrow gap: partial volume
//                decides where each scan's surface lies; analysis/resolution.h). Only for
//                surfaces extracted from volumes.
// Classes are exclusive, in this order: not reached, hole (compared), reference border,
// examined border, below resolution, compared.
//
// How the decision reads them (decision.cpp): the floors and the histogram read compared
// vertices only; the damaged mask every reached vertex, less every connected damaged group
// with more than kBorderMajority of its area in the two border bands (the curl of a cut's
// rows) — a damage that reaches a border is reported whole — or more than
// kBelowResolutionShare of its footprint below the scans' resolution (a thin plate's partial volume).
//
// A hole's shape: a plane is fitted to its rim (the vertices next to it), oriented by the
// reference's normals over the hole. Where the reference stood above that plane on average
// the material is gone: a loss, each vertex's depth minus its height above the rim, a dent
// where it reaches the shape floor. Over a flat or concave patch the rim cannot tell worn-away
// material from surface a scanner never captured, unless the examined surface cannot drop
// out: one that is no one-view scan (a surface extracted from a volume, a crown segmented
// from micro-CT, a scan fused from all round) holds surface wherever the object has some, so
// surface gone inside a rim it covered is material gone. Such a hole is a loss too, whatever
// its shape (hole_loss); its depth is what the reference stood above the rim, a lower bound:
// how far below the rim the material went the examined surface does not show. Only a hole in
// a one-view scan's surface over a flat or concave patch stays depth 0, "missing surface".
#pragma once

#include "mesh/mesh.h"
#include "mesh/scan_view.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace glint {

enum class CompareClass : std::uint8_t {
    Compared = 0,
    ReferenceBorder = 1,  ///< near an open border of the reference
    ExaminedBorder = 2,   ///< near an open border of the examined surface
    NotReached = 3,       ///< the examined surface never covered it
    BelowResolution = 4,  ///< closer to another sheet than the scans' voxels resolve
};

/// "compared", "reference border", "examined border", "not reached", "below resolution".
[[nodiscard]] std::string to_string(CompareClass c);

/// note: 4 edges — a marching-cubes cut or a range scan's ragged edge curls over 1–3 rows of
/// triangles; the band keeps those rows out while costing a few % of a whole surface.
inline constexpr double kBandEdges = 4.0;
/// note: a quarter of the reference's area — the EDJ wear variants remove up to 14 % of the
/// crown (three worn cusps, combined_c0_2_3); a partial scan (a bunny range scan, a one-sided
/// jaw of ≤ 70 % of the surface) leaves ≥ 30 % unscanned.
inline constexpr double kMaxHoleShare = 0.25;
/// note: a gone group holding one run of the reference's open border at least half as long as
/// its rim on reached surface (a third of the two together) is no hole: the strip between two
/// fields of view holds the reference's whole cut, as long as its other side; a hole the scan
/// covered around holds at most small openings of the reference (the EDJ crown has some).
inline constexpr double kMaxOpenRim = 1.0 / 3.0;
/// note: … unless its surface is a cap (|area-weighted mean normal| ≥ half): worn cusps of the
/// EDJ crown hold a long opening of the reference too (390 border vertices against 421 on the
/// rim in tooth_wear_combined_c0_2_3), but are caps, while the strip round a cut bone turns
/// round and its normals cancel. A field-of-view strip over a flat surface stays a hole.
inline constexpr double kMinCapCoherence = 0.5;
/// note: 60° — there a sensor's samples lie twice as far apart on the surface as facing it,
/// and range scans drop out: the Stanford bunny's gone patches inside its scanned side face
/// the scan's axis at 64–81° (area-weighted medians, bun090 and bun315), while the worn
/// cusps of a crown face its occlusal view.
inline constexpr double kGrazingDeg = 60.0;

/// note: a fifth of the square root of the area — a closed surface has no border; a surface
/// segmented from CT or fused from all round may keep a few stray openings (the jaw with its
/// graft: 23 border edges, 13 mm against √area = 137 mm), while a partial scan's outline runs
/// round the part it covers (a one-sided jaw: several hundred mm).
inline constexpr double kMaxEnclosedBorder = 0.2;
/// note: half the reference's area — a segmental resection removes 42 % of a jaw's surface
/// (one side of its body and its ramus); an examined surface holding less than half of the
/// reference is a part of it (a crop closed by a cap), not what is left after a loss.
inline constexpr double kMaxLossShare = 0.5;

/// Whether a surface encloses its solid: its open borders together are shorter than
/// kMaxEnclosedBorder × √(its area), so it holds surface wherever the object has some.
[[nodiscard]] bool encloses(const Mesh& surface);

/// What the classification reads, one value per reference vertex (optional ones may be null).
struct ComparisonInputs {
    const std::vector<std::uint8_t>* seen = nullptr;       ///< required
    const std::vector<float>* missing = nullptr;           ///< required: share without examined
    const std::vector<float>* distance = nullptr;          ///< signed distance (may be null)
    const std::vector<std::uint8_t>* at_border = nullptr;  ///< (may be null)
    /// The closest examined triangle faces away from the vertex's normal (may be null).
    const std::vector<std::uint8_t>* facing_away = nullptr;
    /// The examined surface is a one-view scan taken from this view, in the reference's frame
    /// (may be null: not a one-view scan).
    const ScanView* scan_view = nullptr;
    /// 1: below the scans' resolution (analysis/resolution.h; may be null or empty: none).
    const std::vector<std::uint8_t>* below_resolution = nullptr;
    /// 1: outside the examined scan's field of view, or within a voxel of its cut (may be
    /// null or empty: the field of view is unknown).
    const std::vector<std::uint8_t>* beyond_view = nullptr;
    /// The examined surface encloses its solid (no one-view scan, its open borders together
    /// shorter than kMaxEnclosedBorder × √area): it holds surface wherever the object still
    /// has some, so a gone group of any extent up to kMaxLossShare is material gone.
    bool examined_encloses = false;
};

struct Comparison {
    std::vector<std::uint8_t> vertex_class;  ///< CompareClass per reference vertex
    /// Signed depth of the surface gone in a hole (mesh units, negative = loss, 0 where the
    /// rim cannot tell; NaN outside holes).
    std::vector<float> hole_depth;
    std::vector<std::uint8_t> in_hole;  ///< 1: the vertex lies in a hole (compared, gone)
    /// 1: the vertex's hole is a loss (material gone), whether or not its depth reaches the
    /// shape floor: the reference stood above the hole's rim, or the examined surface is no
    /// one-view scan (see the rule above).
    std::vector<std::uint8_t> hole_loss;
    double edge = 0.0;  ///< the reference's median edge length ℓ (mesh units)
    double band = 0.0;  ///< kBandEdges·ℓ
    double reference_area = 0.0;
    double compared_area = 0.0;
    double reference_border_area = 0.0;
    double examined_border_area = 0.0;
    double not_reached_area = 0.0;
    double below_resolution_area = 0.0;
    std::size_t holes = 0;  ///< gone groups kept as holes (compared)
    double hole_area = 0.0;
    std::size_t lost_holes = 0;  ///< of those, the holes read as a loss (hole_loss)
    double lost_hole_area = 0.0;
    std::optional<ScanView> scan_view;  ///< the examined one-view scan's, reference frame
    std::size_t dropouts = 0;           ///< gone groups at grazing incidence: not reached
    double dropout_area = 0.0;
    /// Gone groups reaching beyond the examined scan's field of view: not reached.
    std::size_t beyond_view = 0;
    double beyond_view_area = 0.0;
    /// The examined surface enclosed its solid (ComparisonInputs::examined_encloses).
    bool examined_encloses = false;
    double fraction = 1.0;  ///< compared / reference area
    std::string rule;       ///< one line: the rule applied
    /// Damaged groups dropped because they lay mostly in a not-compared band (drop_border_groups).
    std::size_t border_groups = 0;

    [[nodiscard]] bool compared(std::size_t v) const {
        return vertex_class.empty() || vertex_class[v] == 0;
    }
};

/// Classifies every reference vertex (see the file comment). \pre the inputs sized as the mesh.
[[nodiscard]] Comparison classify_comparison(const Mesh& reference, const ComparisonInputs& in);

/// note: a half — a damage that straddles a cut or a scan's edge is mostly on compared surface
/// and is kept whole; the curl of a cut's rows lies wholly in its band.
inline constexpr double kBorderMajority = 0.5;

/// note: a tenth. The below-resolution class marks where another sheet lies within one voxel;
/// partial volume still moves the two scans' surfaces where it lies within two or three (the
/// sheets' blur overlaps), so a change that runs on from a thin plate or process into its
/// surroundings is their partial volume, not damage. The share is read over the group's
/// footprint: its vertices and those within the radius its evidence was read over. On CThead's
/// whole bone surface scanned twice (two noise realisations, 1 × 1 × 2 mm against 0.8 mm
/// voxels; evidence at 2.06 mm) the false groups' footprints lay 13–31 % on it, the erosion's 3 %.
inline constexpr double kBelowResolutionShare = 0.1;

/// Clears from a damaged mask the not-reached vertices and every connected group with more
/// than kBorderMajority of its area outside the compared class (a cut's or a scan edge's
/// curl), or more than kBelowResolutionShare below the scans' resolution. The border vertices
/// of a group that lies mostly on compared surface stay in it: a damage reaching a border is
/// reported whole. Returns the groups dropped.
std::size_t drop_border_groups(const Mesh& mesh, std::vector<std::uint8_t>& damaged,
                               const Comparison& c, double radius = 0.0);

}  // namespace glint
