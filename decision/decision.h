// The decision: which parts of the reference surface are damaged, from the evidence a run
// measured, against floors the run estimates from its own undamaged majority.
//
// Evidence per reference vertex and zoom:
//   normal  the metric's footprint-averaged per-vertex mean (ZoomAtlas::value_mean): the
//           paper's signal; its floor says how much two renderings of the same surface differ
//           (tessellation, registration, noise) at this zoom;
//   shape   the signed distance to the fitted examined surface (mesh units; negative = loss),
//           from analysis/fit.h; its floor says how far two tessellations of one surface lie
//           apart.
// A floor is robust: median + k·1.4826·MAD over the seen vertices (1.4826 makes the MAD a
// consistent estimate of σ for Gaussian noise), never below a stated minimum; a floor above
// a plausible limit is capped and reported, never silently absurd.
//
// Rules:
//   normal  the paper's rule: a seen vertex whose normal evidence reaches its floor is
//           damaged; regions are its connected groups.
//   fused   both kinds of evidence, each against its floor:
//           1. shape excess e = sign(d)·max(0, |d| − tolerance): the signed distance beyond
//              what the two tessellations may differ by (analysis/fit.h ShapeEvidence);
//           2. candidates: seen vertices whose excess of one sign reaches the lower shape
//              floor, grouped through mesh edges;
//           3. growth: from the vertices of each group whose excess reaches the shape floor
//              (so tessellation-only normal differences do not count), the extent grows
//              through connected vertices whose signed distance reaches a tenth
//              (grow_fraction) of the group's peak and the lower shape floor, and, below
//              1.5 times that reach, half the local tessellation tolerance — where the shape
//              changed, not only its steep rim;
//           4. the grown extent is a region only when its normal deviation reaches the
//              normal floor's lower level (so isolated distance speckle from noise does not
//              count; a smooth dent turns the normals most on its flanks, not at its core);
//           5. where the examined surface is missing (views found no surface behind the
//              reference, or the closest examined point lies on a border with a large
//              distance) inside the compared surface (a hole, decision/comparison.h) the
//              region is "missing surface", or a dent (loss) where the reference stood
//              above the hole's rim: worn-away or resected material.
//
// Before either rule, the reference is classified (decision/comparison.h): only vertices that
// both surfaces can compare are decided; the rest (open borders of either surface, parts the
// examined scan did not reach) are reported as not compared.
#pragma once

#include "decision/comparison.h"
#include "decision/regions.h"
#include "mesh/mesh.h"
#include "scanner/atlas.h"
#include "scanner/coverage.h"
#include "scanner/metric.h"

#include <optional>
#include <string>
#include <vector>

namespace glint {

enum class DecisionRule { Normal, Fused };
/// "normal" / "fused". \throw InputError.
[[nodiscard]] DecisionRule parse_decision_rule(const std::string& text);
[[nodiscard]] std::string to_string(DecisionRule rule);

struct DecisionOptions {
    DecisionRule rule = DecisionRule::Fused;
    /// Normal evidence: the threshold given (metric units: degrees for angle); else the floor.
    std::optional<double> threshold;
    double noise_k = 6.0;        ///< normal floor: median + k·1.4826·MAD …
    double min_threshold = 2.0;  ///< … never below this (metric units; see README)
    /// A normal floor above this (degrees; scaled to the metric by its colour range) is
    /// implausible: most of the surface would then differ. It is capped and reported.
    double max_plausible_threshold_deg = 20.0;
    /// For meshes read from files: the voxel edge of the scans they came from (mesh units);
    /// surfaces extracted from volumes carry their own grid (analysis/resolution.h).
    std::optional<double> resolution;
    /// Shape evidence: the floor given (mesh units); else estimated.
    std::optional<double> shape_threshold;
    double shape_k = 6.0;      ///< shape floor: median + k·1.4826·MAD of |shape excess| …
    double shape_low_k = 3.0;  ///< lower (hysteresis) floor: median + k_low·1.4826·MAD
    /// … never below this share of the bounding diagonal (the distance's numerical noise).
    double min_shape_fraction = 1e-5;
    /// A shape floor above this share of the bounding diagonal is implausible (capped, reported).
    double max_plausible_shape_fraction = 0.01;
    /// Hysteresis: a region grows from its strong evidence through connected vertices whose
    /// shape change is at least this share of the region's peak (and above the lower floor).
    double grow_fraction = 0.1;
    std::size_t min_region_vertices = 3;
    bool fill_holes = true;
    /// The differences the floors are measured from are the surface's own nature, not noise
    /// of two acquisitions of one object: a surface against its mirror image (analysis/
    /// asymmetry.h), whose natural asymmetry is what a one-sided change must stand above.
    /// Nothing is capped then (a cap below the natural spread would make all of it damage);
    /// the smallest detectable change says what the run can tell. Where the sides' normals
    /// differ beyond `max_plausible_threshold_deg` the normal field cannot corroborate a
    /// change, and the shape decides alone (its floor already stands above the natural
    /// spread). Set by the asymmetry run, not a user option.
    bool natural_floors = false;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

/// How a floor was obtained: estimated from the run (measured), raised to the stated
/// minimum, lowered to the plausible limit (capped: always a warning), or set by the user.
enum class FloorSource { Measured, Minimum, Capped, Given };
[[nodiscard]] std::string to_string(FloorSource source);

/// A floor and how it was obtained.
struct Floor {
    double value = 0.0;  ///< the threshold used (metric units, or mesh units for shape)
    double low =
        0.0;  ///< lower level (k = shape_low_k): shape growth; normal corroboration in the fused rule
    double median = 0.0;
    double mad = 0.0;  ///< raw median absolute deviation
    double k = 0.0;
    double minimum = 0.0;
    double estimate = 0.0;     ///< median + k·1.4826·MAD before the minimum and the cap
    bool given = false;        ///< set by the user, not estimated
    bool implausible = false;  ///< the estimate exceeded the plausible limit and was capped
    /// Normal floors only. false: a natural floor beyond the plausible limit
    /// (DecisionOptions::natural_floors): the normal field neither corroborates a shape change
    /// nor marks missing surface (the metric's missing value is normal evidence too); the
    /// shape decides alone.
    bool corroborates = true;
    FloorSource source = FloorSource::Measured;
    std::string rule;  ///< one line: how it was obtained
    std::string note;  ///< why it is implausible, or why it cannot corroborate; empty otherwise
};

/// Robust floor of values[i] over use[i] != 0 (see file comment), capped at `plausible_max`.
[[nodiscard]] Floor robust_floor(const std::vector<float>& values,
                                 const std::vector<std::uint8_t>& use, double k, double minimum,
                                 double plausible_max);

/// What the decision read.
struct DecisionEvidence {
    const ZoomAtlas* atlas = nullptr;    ///< normal evidence and view of the maxima
    const Coverage* coverage = nullptr;  ///< seen mask
    const std::vector<float>* distance =
        nullptr;  ///< shape evidence (may be null: normal rule only)
    const std::vector<float>* tolerance =
        nullptr;  ///< tessellation tolerance of the distance (may be null)
    const std::vector<std::uint8_t>* at_border =
        nullptr;  ///< closest examined point on a border (may be null)
    const std::vector<std::uint8_t>* facing_away =
        nullptr;  ///< closest examined triangle faces away (may be null)
    /// The examined surface's view when it is a one-view scan, reference frame (may be null).
    const ScanView* scan_view = nullptr;
    /// 1: below the scans' resolution (analysis/resolution.h; may be null: none).
    const std::vector<std::uint8_t>* below_resolution = nullptr;
    /// 1: beyond the examined scan's field of view (decision/comparison.h; may be null: unknown).
    const std::vector<std::uint8_t>* beyond_view = nullptr;
    /// The examined surface encloses its solid (decision/comparison.h ComparisonInputs).
    bool examined_encloses = false;
    /// Per reference vertex, the coarser scan grid's staircase step along its normal
    /// (analysis/resolution.h staircase_step; mesh units; may be null or empty: no grid). Where
    /// it is large (faces nearly along thick slices) each scan's surface steps by it, and the
    /// distance between two scans on different grids spreads more: the fused rule measures the
    /// spread per band of this step (decision.cpp).
    const std::vector<float>* sampling = nullptr;
    /// The coarser scan's voxel, its longest edge (mesh units; 0: unknown, meshes from files
    /// without --resolution). The fused rule reads the evidence no finer than it: within a
    /// voxel, noise and partial volume, not the object, shape a scan's surface.
    double voxel = 0.0;
    Metric metric = Metric::AngleDeg;
    double size = 1.0;  ///< bounding diagonal of the reference (mesh units)
    std::string unit;   ///< the mesh unit ("mm"), for sentences; empty: "units"
};

/// The scale the fused rule read its evidence at. Where the floors at the vertices' own scale
/// are implausible (a cap was hit: rough surfaces, CT staircase and partial-volume noise), the
/// shape evidence is read over growing radii (decision/detail/evidence_scale.h) until the
/// undamaged majority is quiet (neither floor implausible); the first such radius is chosen,
/// and regions are also sought over the two rungs beyond it (`wider`: a wider, shallower
/// change stands out only there). Where none is quiet, no region is reported: dozens of noise
/// regions would say nothing.
struct EvidenceScale {
    double radius = 0.0;  ///< 0: each vertex's own evidence
    /// The floors at the vertices' own scale were implausible, or the scans' voxel is known
    /// (DecisionEvidence::voxel): the evidence was read over a radius.
    bool searched = false;
    bool quiet = true;       ///< false: no scale tried made the majority quiet (no regions)
    double min_depth = 0.0;  ///< smallest detectable depth there (mesh units)
    double min_area = 0.0;   ///< smallest detectable area there (mesh units²)
    /// The shape floor plus the median tessellation tolerance there (mesh units): min_depth
    /// before the data's resolution bounds it.
    double floor_depth = 0.0;
    /// Where the distance was read per band of the grid's staircase step along the normal
    /// (decision.cpp SamplingBands): the smallest detectable depth where faces lie along the
    /// thickest slices (min_depth holds it for the quietest band), and each band's spread (mesh units).
    double min_depth_across = 0.0;
    /// The data's resolution, below which no depth is stated detectable: half the reference's
    /// median edge (mesh units).
    double resolution_depth = 0.0;
    std::vector<double> sampling_bands;
    /// The smallest detectable damage at each scale from the one read up to the largest of the
    /// ladder (decision.cpp detection_limit): a wider change is told at a shallower depth, as
    /// the undamaged surface's spread averages down over wider discs. Each point's area is one
    /// resolution element of its scale, its depth the shape floor plus the typical tessellation
    /// tolerance there, never below resolution_depth (mesh units, mesh units²).
    struct LimitPoint {
        double radius = 0.0;
        double area = 0.0;
        double depth = 0.0;
        double depth_across = 0.0;  ///< where faces lie across the thickest slices (bands used)
    };
    std::vector<LimitPoint> limit_curve;
    /// The resolution elements searched (compared area over one element's area, at the scale
    /// read): the number of places a false alarm could arise, for the regions' p values.
    double resels = 0.0;
    std::vector<double> tried;  ///< radii tried, in order
    /// The wider rungs searched for regions beyond the chosen radius (decision.cpp
    /// search_wider): a change wider than the chosen scale stands out only where its disc's
    /// spread has averaged down. Regions' p values count every scale searched.
    std::vector<double> wider;
    Floor own_normal;  ///< the floors at the vertices' own scale (when searched)
    Floor own_shape;
    std::string text;  ///< one line: the scale and what it can detect
};

struct ZoomDecision {
    DecisionRule rule = DecisionRule::Normal;
    std::string rule_text;  ///< one line stating the rule applied
    Floor normal;
    Floor shape;          ///< unset (rule empty) for the normal rule
    EvidenceScale scale;  ///< the fused rule's scale (radius 0 for the normal rule)
    /// What both surfaces can compare (decision/comparison.h); floors, regions and the
    /// histogram read the compared vertices only.
    Comparison comparison;
    RegionResult regions;
    std::vector<std::size_t> histogram;  ///< normal evidence of seen vertices (metric's bins)
    std::vector<std::string> warnings;   ///< implausible floors, fallbacks
};

/// Applies the rule to one zoom level. \throw InputError invalid options.
[[nodiscard]] ZoomDecision decide(const Mesh& reference, const DecisionEvidence& evidence,
                                  const DecisionOptions& options);

/// The shape change a zoom's regions read, one value per reference vertex (mesh units): the
/// signed `distance`, and in a hole of `d.comparison` the depth of the surface gone (the hole's
/// depth where it is a loss or reaches the shape floor, 0 where no loss is measurable). In a
/// hole the signed distance only measures to the rim or the far side, so pictures paint this.
/// NaN where the examined surface never reached (CompareClass::NotReached): the distance
/// there is to surface elsewhere, no shape change.
[[nodiscard]] std::vector<float> decided_shape(const std::vector<float>& distance,
                                               const ZoomDecision& d);

}  // namespace glint
