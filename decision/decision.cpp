#include "decision/decision.h"

#include "decision/detail/evidence_scale.h"
#include "decision/detail/fused_rule.h"
#include "mesh/components.h"
#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <sstream>

namespace glint {

namespace {

std::string fixed(double v, int digits) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(digits);
    s << v;
    return s.str();
}

std::string general(double v) {
    std::ostringstream s;
    s.precision(3);
    s << v;
    return s.str();
}

double median_of(std::vector<float>& v) {
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return static_cast<double>(*mid);
}

std::vector<std::size_t> histogram_of(const std::vector<float>& value,
                                      const std::vector<std::uint8_t>& seen,
                                      const MetricDescriptor& m) {
    const auto bins = static_cast<std::size_t>(std::ceil(m.histogram_max / m.histogram_bin));
    std::vector<std::size_t> h(bins + 1, 0);  // the last bin: ≥ histogram_max
    for (std::size_t v = 0; v < value.size(); ++v)
        if (seen[v])
            ++h[std::min(bins,
                         static_cast<std::size_t>(std::max(0.0f, value[v]) / m.histogram_bin))];
    return h;
}

// An estimated floor as a sentence may state it: an angle floor beyond 180° is no angle (the
// median and the MAD, each at most 180°, are stated instead).
std::string stated_estimate(const Floor& f, const MetricDescriptor& m) {
    const std::string sym(m.symbol);
    if (&m == &describe(Metric::AngleDeg) && f.estimate > 180.0)
        return "(median " + fixed(f.median, 2) + sym + " + " + general(f.k) + "·1.4826·MAD " +
               fixed(f.mad, 2) + sym + ", beyond 180" + sym + ")";
    return fixed(f.estimate, 2) + sym;
}

// The normal-evidence floor: given, or the run's noise floor.
// `with_surface_only`: over the seen vertices with an examined surface (at a chosen scale:
// the missing surface is no part of the majority whose quiet the scale is chosen for).
Floor normal_floor(const DecisionEvidence& e, const DecisionOptions& o, const MetricDescriptor& m,
                   bool with_surface_only = false) {
    const double limit =
        o.max_plausible_threshold_deg * m.color_max / describe(Metric::AngleDeg).color_max;
    const double plausible = o.natural_floors ? std::numeric_limits<double>::infinity() : limit;
    Floor f;
    if (o.threshold) {
        f.value = *o.threshold;
        f.low = f.value;
        f.given = true;
        f.source = FloorSource::Given;
        f.rule = "given";
        return f;
    }
    std::vector<std::uint8_t> use = e.coverage->seen;
    if (with_surface_only)
        for (std::size_t v = 0; v < use.size(); ++v) use[v] = use[v] && e.atlas->missing[v] <= 0.5f;
    f = robust_floor(e.atlas->value_mean, use, o.noise_k, o.min_threshold, plausible);
    // The fused rule asks the normal field for corroboration of a shape change, not for proof
    // on its own: the lower floor (k = shape_low_k, as for the shape) is what a group must reach.
    f.low = std::min(f.value, std::max(f.median + o.shape_low_k * 1.4826 * f.mad, o.min_threshold));
    f.rule = "median + " + general(o.noise_k) + "·1.4826·MAD of the per-vertex mean " +
             std::string(m.name) + " over seen vertices, at least " + general(o.min_threshold) +
             std::string(m.symbol);
    if (o.natural_floors && f.value > limit) {
        // decision.h natural_floors: no corroboration where the normals differ this much
        // by nature; the shape floor (above the natural spread) decides alone.
        f.low = o.min_threshold;
        f.corroborates = false;
        f.note = "the surface's normals differ from its mirror image's by nature (median " +
                 fixed(f.median, 2) + std::string(m.symbol) + ", floor " + stated_estimate(f, m) +
                 ", beyond " + fixed(limit, 1) + std::string(m.symbol) +
                 "): the normal field cannot corroborate a change; the shape decides alone";
    }
    if (f.implausible)
        f.note = "the estimated floor " + stated_estimate(f, m) + " exceeds the plausible " +
                 fixed(plausible, 1) + std::string(m.symbol) +
                 ": more than half of the seen surface differs (a large edit, a poor fit, rough "
                 "surfaces, or surfaces that do not correspond); capped at " +
                 fixed(plausible, 1) + std::string(m.symbol);
    return f;
}

// The shape-evidence floor over |excess| of seen vertices with an examined surface.
Floor shape_floor(const DecisionEvidence& e, const std::vector<float>& excess,
                  const DecisionOptions& o) {
    Floor f;
    if (o.shape_threshold) {
        f.value = *o.shape_threshold;
        f.low = 0.5 * f.value;
        f.given = true;
        f.source = FloorSource::Given;
        f.rule = "given (lower floor: half of it)";
        return f;
    }
    // The scale is the spread of the signed distance over the undamaged majority (tessellation,
    // registration and noise together), the location the median of the excess. Beyond the
    // tessellation tolerance most vertices have no excess at all, so the excess's own MAD is
    // zero and would make any speck a shape change.
    std::vector<float> distance;
    std::vector<float> magnitude;
    for (std::size_t v = 0; v < excess.size(); ++v) {
        if (!e.coverage->seen[v] || e.atlas->missing[v] > 0.5f || !std::isfinite(excess[v]))
            continue;
        distance.push_back((*e.distance)[v]);
        magnitude.push_back(std::abs(excess[v]));
    }
    const std::vector<std::uint8_t> all(distance.size(), 1);
    const Floor spread =
        robust_floor(distance, all, o.shape_k, 0.0, std::numeric_limits<double>::infinity());
    const double minimum = o.min_shape_fraction * e.size;
    const double plausible = o.natural_floors ? std::numeric_limits<double>::infinity()
                                              : o.max_plausible_shape_fraction * e.size;
    f.k = o.shape_k;
    f.minimum = minimum;
    f.mad = spread.mad;
    f.median = magnitude.empty() ? 0.0 : median_of(magnitude);
    const double sigma = 1.4826 * f.mad;
    f.estimate = f.median + o.shape_k * sigma;
    f.value = std::max(f.estimate, minimum);
    f.source = f.estimate < minimum ? FloorSource::Minimum : FloorSource::Measured;
    if (f.value > plausible) {
        f.implausible = true;
        f.source = FloorSource::Capped;
        f.value = std::max(plausible, minimum);
    }
    f.low = std::min(f.value, std::max(f.median + o.shape_low_k * sigma, minimum));
    f.rule =
        "median of the shape excess (|d| − tessellation tolerance) + " + general(o.shape_k) +
        "·1.4826·MAD of the signed distance d, over seen vertices with an examined surface, at least " +
        general(o.min_shape_fraction) +
        " × the size; lower floor with k = " + general(o.shape_low_k);
    if (f.implausible)
        f.note =
            "the estimated shape floor " + general(f.estimate) + " exceeds " +
            general(o.max_plausible_shape_fraction * 100) +
            " % of the size: more than half of the seen surface moved (a large edit, a poor fit, or different "
            "surfaces); capped at " +
            general(plausible);
    return f;
}

// e = sign(d)·max(0, |d| − tolerance) (decision.h, fused rule step 1).
std::vector<float> shape_excess(const DecisionEvidence& e) {
    const auto& d = *e.distance;
    std::vector<float> excess(d.size());
    for (std::size_t v = 0; v < d.size(); ++v) {
        const float tol = e.tolerance && e.tolerance->size() == d.size() ? (*e.tolerance)[v] : 0.0f;
        excess[v] = std::copysign(std::max(0.0f, std::abs(d[v]) - tol), d[v]);
    }
    return excess;
}

std::string fused_rule_text(const ZoomDecision& d, const MetricDescriptor& m) {
    if (!d.normal.corroborates)
        return "fused, shape alone: a region holds a shape change beyond the tessellation "
               "tolerance of at least " +
               general(d.shape.value) + " (grown from " + general(d.shape.low) +
               "); the normal field cannot corroborate (the normal floor " +
               fixed(d.normal.value, 2) + std::string(m.symbol) +
               " is the surface's nature) and marks no missing surface; its extent reaches a "
               "tenth of its peak shape change";
    return "fused: a region holds a shape change beyond the tessellation tolerance of at least " +
           general(d.shape.value) + " (grown from " + general(d.shape.low) +
           ") and a per-vertex mean " + std::string(m.name) + " of at least " +
           fixed(d.normal.low, 2) + std::string(m.symbol) + " (the normal floor's lower level)" +
           "; its extent reaches a tenth of its peak shape change";
}

std::vector<std::uint8_t> normal_rule_mask(const DecisionEvidence& e, const Floor& normal) {
    const auto& value = e.atlas->value_mean;
    std::vector<std::uint8_t> damaged(value.size(), 0);
    for (std::size_t v = 0; v < value.size(); ++v)
        damaged[v] = e.coverage->seen[v] && value[v] >= normal.value;
    return damaged;
}

// In holes (decision/comparison.h) the depth of the surface gone where it reaches the shape
// floor or where the hole is a loss whatever its depth (Comparison::hole_loss: then a lower
// bound), 0 where the loss is not measurable (a one-view scan's flat patch); NaN outside holes.
std::vector<float> gone_depth(const Comparison& c, double floor) {
    std::vector<float> gone(c.hole_depth.size(), std::numeric_limits<float>::quiet_NaN());
    const bool have_loss = c.hole_loss.size() == gone.size();
    for (std::size_t v = 0; v < gone.size(); ++v) {
        if (!c.in_hole[v] || std::isnan(c.hole_depth[v])) continue;  // unknown stays unknown
        const bool loss = have_loss && c.hole_loss[v];
        gone[v] = loss || c.hole_depth[v] <= -floor ? c.hole_depth[v] : 0.0f;
    }
    return gone;
}

// The shape change the regions report: the signed distance, and in a hole the depth of the
// surface gone (NaN where it is unknown: the distance to the hole's rim says nothing).
std::vector<float> region_shape(const std::vector<float>& distance, const Comparison& c,
                                const std::vector<float>& gone) {
    std::vector<float> shape = distance;
    for (std::size_t v = 0; v < shape.size() && v < c.in_hole.size(); ++v)
        if (c.in_hole[v]) shape[v] = gone[v];
    return shape;
}

// The fields the regions read; the store owns what they point at.
struct RegionFieldStore {
    std::vector<float> gone;
    std::vector<float> shape;
    RegionFields fields;
};

void build_fields(const DecisionEvidence& e, const Comparison& c, double shape_floor,
                  RegionFieldStore& s) {
    const bool have_distance = e.distance && e.distance->size() == e.atlas->value_mean.size();
    const std::vector<float>& distance = have_distance ? *e.distance : e.atlas->depth_mean;
    s.gone = gone_depth(c, shape_floor);
    s.shape = region_shape(distance, c, s.gone);
    s.fields = RegionFields{.value = &e.atlas->value_mean,
                            .shape = &s.shape,
                            .missing = &e.atlas->missing,
                            .view = &e.atlas->max_view,
                            .gone = &s.gone,
                            .gone_loss = c.hole_loss.empty() ? nullptr : &c.hole_loss};
}

// The fused rule's floors from evidence `e` (one scale).
struct FusedAtScale {
    Floor normal;
    Floor shape;
    std::vector<float> excess;
};

// The floors read the compared vertices only (`compared`, decision/comparison.h): surface near
// a border or beyond the examined scan is no part of the majority that sets the noise floor.
FusedAtScale fused_floors(const DecisionEvidence& e, const Coverage& compared,
                          const DecisionOptions& o, bool with_surface_only = false) {
    DecisionEvidence over = e;
    over.coverage = &compared;
    FusedAtScale f;
    f.excess = shape_excess(e);
    f.normal = normal_floor(over, o, describe(e.metric), with_surface_only);
    f.shape = shape_floor(over, f.excess, o);
    return f;
}

// The damaged mask less the groups that lie mostly in a not-compared band
// (decision/comparison.h drop_border_groups), counted in the comparison.
std::vector<std::uint8_t> off_borders(const Mesh& reference, std::vector<std::uint8_t> mask,
                                      ZoomDecision& d) {
    d.comparison.border_groups += drop_border_groups(reference, mask, d.comparison, d.scale.radius);
    return mask;
}

// The median edge length of a mesh (0 for none).
double median_edge_of(const Mesh& m) {
    std::vector<float> edge;
    edge.reserve(m.triangle_count());
    for (const auto& t : m.triangles)
        edge.push_back((m.positions[t[0]] - m.positions[t[1]]).norm());
    return edge.empty() ? 0.0 : median_of(edge);
}

// The area of one resolution element of the evidence read over radius r: the disc where the
// fit's Gaussian weights (σ = r/2) stand above half their peak, radius σ·√(2 ln 2) = 0.589·r.
// One vertex's noise, read at this scale, spreads over that disc; a group smaller than it is
// no wider than what a single sample makes, so it is not told from noise.
double resolution_element_area(double r) {
    const double half = 0.5 * r * std::sqrt(2.0 * std::numbers::ln2);
    return std::numbers::pi * half * half;
}

// The smallest damage the rule can tell at a scale: a change deeper than the shape floor
// beyond the typical tessellation tolerance, at least as wide as the smoothing disc (at the
// vertices' own scale: the smallest region kept). Never stated below the data's resolution
// (issue 50): half the reference's median edge, the finest its surface samples the object (a
// CT surface's edges are about a voxel; a floor measured on two copies of one tessellation
// can be a thousandth of that).
void state_detectable(const Mesh& reference, const DecisionEvidence& e, const DecisionOptions& o,
                      const Floor& shape, EvidenceScale& s) {
    std::vector<float> tol;
    if (e.tolerance && e.tolerance->size() == reference.vertex_count())
        for (std::size_t v = 0; v < e.tolerance->size(); ++v)
            if (e.coverage->seen[v]) tol.push_back((*e.tolerance)[v]);
    s.min_depth = shape.value + (tol.empty() ? 0.0 : median_of(tol));
    s.floor_depth = s.min_depth;
    s.resolution_depth = 0.5 * median_edge_of(reference);
    s.min_depth = std::max(s.min_depth, s.resolution_depth);
    const double vertex_area = surface_area(reference) / static_cast<double>(std::max<std::size_t>(
                                                             1, reference.vertex_count()));
    s.min_area = s.radius > 0 ? resolution_element_area(s.radius)
                              : static_cast<double>(o.min_region_vertices) * vertex_area;
    s.text = (s.radius > 0 ? "evidence read over a radius of " + with_unit(s.radius, e.unit)
                           : std::string("each vertex's own evidence")) +
             "; the smallest detectable damage: " + with_unit(s.min_depth, e.unit) + " deep over " +
             with_unit(s.min_area, e.unit, 2, "%.3g") +
             (s.min_depth <= s.resolution_depth
                  ? " (the data's resolution: half the surface's median edge)"
                  : "");
}

// The evidence of `e` read over radius r: the fit's distance, tolerance and tilt (the tilt as
// the normal evidence, in degrees; vertices without an examined surface keep theirs).
struct EvidenceAtScale {
    detail::ScaledEvidence scaled;
    ZoomAtlas atlas;
    DecisionEvidence evidence;
};

void read_at_scale(const Mesh& reference, const DecisionEvidence& e, double r, EvidenceAtScale& s,
                   bool sparse = false) {
    s.scaled = sparse ? detail::sparse_scaled_evidence(reference, e, r)
                      : detail::scaled_evidence(reference, e, r);
    s.atlas = *e.atlas;
    for (std::size_t v = 0; v < s.atlas.value_mean.size(); ++v)
        if (s.atlas.missing[v] <= 0.5f) s.atlas.value_mean[v] = s.scaled.tilt_deg[v];
    s.evidence = e;
    s.evidence.atlas = &s.atlas;
    s.evidence.distance = &s.scaled.distance;
    s.evidence.tolerance = &s.scaled.tolerance;
    s.evidence.metric = Metric::AngleDeg;
}

// Faces along thick slices (DecisionEvidence::sampling): a scan's surface is a staircase whose
// step is the grid's along the normal (the slice thickness where a face lies nearly along the
// slices), and two scans on different grids, or one grid under a motion, differ there by more
// than where a face crosses the grid diagonally: on CThead's 1 x 1 x 2 mm grid under a 3°
// motion the distance's spread grows 3.4 times from the smallest step to the largest. One floor
// over all would either call the terraces of a skull's vault damage or be blind elsewhere. So
// the null is measured per band of that step, on the pair itself: the compared vertices with an
// examined surface fall into up to kSamplingBands bands of equal count (a band of fewer than
// kMinBandVertices joins its neighbour); in each, the distance's median and robust spread
// (1.4826·MAD); the distance (and its tolerance) is then read in units of the quietest band's
// spread, centred on its band's median. A change stands out when it stands out from the surface
// that was sampled as it was.
// note: the step, not the voxel's width along the normal (Σ|n·a_i|, largest on the diagonal):
// with the width, the CThead erosion (normal (-0.56, -0.68, -0.46): width 2.16 mm, step 0.92 mm)
// shared the loudest band with the vault's terraces (normal within 8° of the slices' axis) and
// two 1 mm terraces were the only regions; with the step the erosion stands 12 spreads deep at
// 2.2 mm and no terrace reaches 5.
constexpr std::size_t kSamplingBands = 8;
// Fewer vertices per band than this measure no spread worth trusting: the band joins the next.
constexpr std::size_t kMinBandVertices = 400;
// Bands whose spreads differ by less than this ratio are one population: left as it is.
constexpr double kMinBandRatio = 1.25;

struct SamplingBands {
    std::vector<float> edges;  ///< kSamplingBands − 1 inner edges (mesh units)
    std::vector<double> median;
    std::vector<double> sigma;
    double quietest = 0.0;  ///< the smallest band spread (the unit the distance is read in)
    double loudest = 0.0;
    bool used = false;

    [[nodiscard]] std::size_t band(float width) const {
        return static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), width) -
                                        edges.begin());
    }
};

SamplingBands sampling_bands(const DecisionEvidence& e, const Coverage& compared,
                             const std::vector<float>& distance) {
    SamplingBands b;
    if (!e.sampling || e.sampling->size() != distance.size()) return b;
    const auto& w = *e.sampling;
    const auto usable = [&](std::size_t v) {
        return compared.seen[v] && e.atlas->missing[v] <= 0.5f && std::isfinite(distance[v]) &&
               w[v] > 0.0f;
    };
    std::vector<float> widths;
    for (std::size_t v = 0; v < distance.size(); ++v)
        if (usable(v)) widths.push_back(w[v]);
    if (widths.size() < 2 * kMinBandVertices) return b;
    std::sort(widths.begin(), widths.end());
    // Edges at the quantiles, each once (a grid-aligned surface has few distinct widths); a band
    // left with too few vertices joins the next.
    for (std::size_t k = 1; k < kSamplingBands; ++k) {
        const float edge = widths[k * widths.size() / kSamplingBands];
        if (b.edges.empty() || edge > b.edges.back()) b.edges.push_back(edge);
    }
    for (bool merged = true; merged && !b.edges.empty();) {
        merged = false;
        std::vector<std::size_t> count(b.edges.size() + 1, 0);
        for (const float x : widths) ++count[b.band(x)];
        for (std::size_t k = 0; k < count.size(); ++k)
            if (count[k] < kMinBandVertices) {
                b.edges.erase(b.edges.begin() +
                              static_cast<std::ptrdiff_t>(std::min(k, b.edges.size() - 1)));
                merged = true;
                break;
            }
    }
    if (b.edges.empty()) return SamplingBands{};
    std::vector<std::vector<float>> in(b.edges.size() + 1);
    for (std::size_t v = 0; v < distance.size(); ++v)
        if (usable(v)) in[b.band(w[v])].push_back(distance[v]);
    b.quietest = std::numeric_limits<double>::infinity();
    for (auto& x : in) {
        const double med = median_of(x);
        for (auto& d : x) d = static_cast<float>(std::abs(d - med));
        const double sigma = 1.4826 * median_of(x);
        if (!(sigma > 0.0)) return SamplingBands{};
        b.median.push_back(med);
        b.sigma.push_back(sigma);
        b.quietest = std::min(b.quietest, sigma);
        b.loudest = std::max(b.loudest, sigma);
    }
    b.used = b.loudest > kMinBandRatio * b.quietest;
    return b;
}

// The distance and its tolerance read in units of the quietest band (above).
void read_in_bands(const SamplingBands& b, const std::vector<float>& width,
                   std::vector<float>& distance, std::vector<float>& tolerance) {
    if (!b.used) return;
    for (std::size_t v = 0; v < distance.size(); ++v) {
        const std::size_t k = b.band(width[v]);
        const double scale = b.quietest / b.sigma[k];
        distance[v] = static_cast<float>((distance[v] - b.median[k]) * scale);
        if (v < tolerance.size()) tolerance[v] = static_cast<float>(tolerance[v] * scale);
    }
}

// The smallest detectable damage over wider discs (EvidenceScale::limit_curve): at each rung
// of the ladder from the one read, the evidence is read as for the decision (banded, floors on
// the compared vertices) at every few vertices, enough for the floor's median and MAD: the
// curve costs a fraction of one full reading (CThead's 300k-vertex skull: a strided reading of
// ~10 000 vertices per rung, enough for eight bands of 400 and their medians and MADs).
constexpr std::size_t kLimitSamples = 10000;

EvidenceScale::LimitPoint limit_point(const Mesh& reference, const DecisionEvidence& e,
                                      const Coverage& compared, const DecisionOptions& o,
                                      double r) {
    const std::size_t stride = std::max<std::size_t>(1, reference.vertex_count() / kLimitSamples);
    detail::ScaledEvidence scaled = detail::scaled_evidence(reference, e, r, stride);
    DecisionEvidence at = e;
    at.distance = &scaled.distance;
    at.tolerance = &scaled.tolerance;
    // The compared vertices that were fitted: the others hold NaN.
    Coverage fitted = compared;
    for (std::size_t v = 0; v < fitted.seen.size(); ++v)
        fitted.seen[v] = fitted.seen[v] && std::isfinite(scaled.distance[v]);
    const SamplingBands bands = sampling_bands(at, fitted, scaled.distance);
    if (e.sampling) read_in_bands(bands, *e.sampling, scaled.distance, scaled.tolerance);
    DecisionEvidence over = at;
    over.coverage = &fitted;
    const Floor shape = shape_floor(over, shape_excess(at), o);
    std::vector<float> tol;
    for (std::size_t v = 0; v < scaled.tolerance.size(); ++v)
        if (fitted.seen[v]) tol.push_back(scaled.tolerance[v]);
    EvidenceScale::LimitPoint p;
    p.radius = r;
    p.area = resolution_element_area(r);
    p.depth = shape.value + (tol.empty() ? 0.0 : median_of(tol));
    p.depth_across = bands.used ? p.depth * bands.loudest / bands.quietest : p.depth;
    return p;
}

// The limit at the scale read, then at each wider rung (never below the data's resolution; a
// rung whose floors say nothing, a reading too sparse for bands, is left out).
void state_limit_curve(const Mesh& reference, const DecisionEvidence& e, const Coverage& compared,
                       const DecisionOptions& o, const std::vector<double>& ladder,
                       EvidenceScale& s) {
    s.limit_curve.push_back({s.radius, s.min_area, s.min_depth,
                             s.min_depth_across > 0 ? s.min_depth_across : s.min_depth});
    for (const double r : ladder) {
        if (r <= s.radius) continue;
        EvidenceScale::LimitPoint p = limit_point(reference, e, compared, o, r);
        if (!(p.depth > 0) || !std::isfinite(p.depth)) continue;
        p.depth = std::max(p.depth, s.resolution_depth);
        p.depth_across = std::max(p.depth_across, p.depth);
        s.limit_curve.push_back(p);
    }
    if (s.limit_curve.size() < 2) return;
    std::string wider;
    for (std::size_t k = 1; k < s.limit_curve.size(); ++k)
        if (s.limit_curve[k].depth < s.limit_curve[k - 1].depth)
            wider += (wider.empty() ? "" : ", ") + with_unit(s.limit_curve[k].depth, e.unit) +
                     " over " + with_unit(s.limit_curve[k].area, e.unit, 2, "%.3g");
    s.text += wider.empty() ? "; no shallower over wider areas (up to " +
                                  with_unit(s.limit_curve.back().area, e.unit, 2, "%.3g") + ")"
                            : "; wider: " + wider;
}

// The smallest depth the run can tell at each vertex (RegionOptions::min_depth): the floor's
// depth (EvidenceScale::floor_depth, the quietest band's) as deep in the vertex's band as that
// band's spread is wider, never less than the data's resolution (half the median edge, not
// scaled: it is no spread) nor half the grid's staircase step along the normal: a change
// shallower than half a step is where two samplings of one surface put it.
// note: on CThead's two-acquisition pair (1 x 1 x 2 mm against 0.8 mm, own noise in each) the
// only regions beside the erosion (1.73 mm) were a 0.48 mm dent of 8.9 mm² and a 0.52 mm
// surface gone of 6.9 mm², both shallower than the stated 0.52 mm there or half a step.
std::vector<float> depth_limit(const Mesh& reference, const DecisionEvidence& e,
                               const SamplingBands& bands, const EvidenceScale& s) {
    const std::size_t n = reference.vertex_count();
    const bool stepped = e.sampling && e.sampling->size() == n;
    std::vector<float> limit(n, static_cast<float>(std::max(s.floor_depth, s.resolution_depth)));
    for (std::size_t v = 0; v < n && stepped; ++v) {
        const float step = (*e.sampling)[v];
        const double band = bands.used ? bands.sigma[bands.band(step)] / bands.quietest : 1.0;
        limit[v] = static_cast<float>(
            std::max({s.floor_depth * band, s.resolution_depth, 0.5 * static_cast<double>(step)}));
    }
    return limit;
}

// The vertices of the damaged groups off_borders dropped: `candidates` less `kept`.
std::vector<std::uint8_t> border_groups(const std::vector<std::uint8_t>& candidates,
                                        const std::vector<std::uint8_t>& kept) {
    std::vector<std::uint8_t> dropped(candidates.size(), 0);
    for (std::size_t v = 0; v < candidates.size(); ++v) dropped[v] = candidates[v] && !kept[v];
    return dropped;
}

// How strongly each region stands out (Region::z, Region::p_value). The undamaged surface's
// spread is the shape floor's (1.4826·MAD of the distance on the compared vertices at the scale
// read), its location the median excess. A region's z is its strongest |excess| in that unit.
// Two family-wise bounds over the `resels` resolution elements searched, the larger reported:
//   Gaussian  resels · P(|N(0,1)| ≥ z): what a noise field with the measured spread would give
//             somewhere (Bonferroni over independent elements; conservative for a smooth field);
//   measured  the number of places on the compared surface outside every region — connected
//             groups of vertices whose |excess| reaches the region's own strongest and whose
//             normal evidence reaches the normal floor's lower level (the conjunction a region
//             needs), outside the groups dropped along borders (scan edges, not surface) — at
//             least one resolution element wide: how often the pair's own undamaged surface
//             makes a place a region could be, that high (heavy tails — terraces, streaks —
//             that a Gaussian misses). Isolated vertices as high are no such place: counting
//             their area put p at 1 for a 16σ erosion.
// Surface gone and missing surface are no distances: they keep NaN.
void state_significance(const Mesh& reference, const Coverage& compared, const DecisionEvidence& at,
                        const std::vector<float>& excess, const std::vector<std::uint8_t>& border,
                        double element_area, ZoomDecision& d) {
    const std::size_t n = reference.vertex_count();
    if (excess.size() != n || d.regions.region_of_vertex.size() != n || !(element_area > 0)) return;
    const double sigma = 1.4826 * d.shape.mad;
    if (!(sigma > 0)) return;
    const auto area = vertex_areas(reference);
    std::vector<float> peak(d.regions.regions.size() + 1, 0.0f);
    std::vector<std::uint8_t> in_null(n, 0);
    double compared_area = 0.0;
    for (std::size_t v = 0; v < n; ++v) {
        if (!compared.seen[v] || !std::isfinite(excess[v])) continue;
        compared_area += area[v];
        const auto id = static_cast<std::size_t>(d.regions.region_of_vertex[v]);
        if (id > 0 && id < peak.size()) peak[id] = std::max(peak[id], std::abs(excess[v]));
        else if (id == 0 && !border[v] &&
                 (!d.normal.corroborates || at.atlas->value_mean[v] >= d.normal.low))
            in_null[v] = 1;
    }
    d.scale.resels = compared_area / element_area;
    // The null's places: connected groups of null vertices at least as high as a region's peak,
    // counted where they are as wide as a region must be (one resolution element). A place
    // narrower than that the rule could never report, whatever its height.
    std::vector<std::uint8_t> mask(n, 0);
    std::vector<std::int32_t> component;
    for (auto& r : d.regions.regions) {
        if (r.kind == RegionKind::MissingSurface || r.is_hole_loss()) continue;
        const float top = peak[static_cast<std::size_t>(r.id)];
        r.z = (top - d.shape.median) / sigma;
        for (std::size_t v = 0; v < n; ++v) mask[v] = in_null[v] && std::abs(excess[v]) >= top;
        const std::size_t count = masked_components(reference, mask, component);
        std::vector<double> group_area(count, 0.0);
        for (std::size_t v = 0; v < n; ++v)
            if (component[v] >= 0) group_area[static_cast<std::size_t>(component[v])] += area[v];
        const auto as_high = static_cast<double>(std::count_if(
            group_area.begin(), group_area.end(), [&](double a) { return a >= element_area; }));
        const double gaussian = d.scale.resels * std::erfc(r.z / std::numbers::sqrt2);
        // note: erfc underflows to 0 beyond z ≈ 38; a p is never 0, so it is stated no smaller
        // than the smallest normal double (report.json wrote 0 for the CThead 5 mm erosion).
        r.p_value =
            std::min(1.0, std::max({gaussian, as_high, std::numeric_limits<double>::min()}));
    }
}

// Where the evidence reaches the stated limit but no region holds it (issue 50, item 5): the
// compared vertices outside every region whose shape excess at the chosen scale reaches the
// shape floor, grouped by sign through mesh edges; a group at least as large as the smallest
// detectable area is a change the statement says the run can tell, which it did not report.
// One warning names the largest such group, where it lies and why it is no region.
std::optional<std::string> unreported_change(const Mesh& reference, const Coverage& compared,
                                             const DecisionEvidence& at,
                                             const std::vector<float>& excess,
                                             const std::vector<float>& raw, const ZoomDecision& d,
                                             const std::string& unit) {
    const std::size_t n = reference.vertex_count();
    if (excess.size() != n || raw.size() != n || d.regions.region_of_vertex.size() != n)
        return std::nullopt;
    const auto area = vertex_areas(reference);
    struct Group {
        double area = 0.0, peak = 0.0, tilt = 0.0;
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    };
    Group best;
    std::size_t groups = 0;
    for (const double sign : {-1.0, 1.0}) {
        std::vector<std::uint8_t> mask(n, 0);
        for (std::size_t v = 0; v < n; ++v)
            mask[v] = compared.seen[v] && d.regions.region_of_vertex[v] == 0 &&
                      (d.comparison.in_hole.size() != n || !d.comparison.in_hole[v]) &&
                      at.atlas->missing[v] <= 0.5f && sign * excess[v] >= d.shape.value;
        std::vector<std::int32_t> component;
        const std::size_t count = masked_components(reference, mask, component);
        // A group that touches a region is that region's spill (the smoothing at the chosen
        // scale carries its change a disc beyond its border): the region is the finding there.
        std::vector<std::uint8_t> borders_region(count, 0);
        for (const auto& t : reference.triangles) {
            bool in_region = false;
            for (const auto v : t) in_region = in_region || d.regions.region_of_vertex[v] != 0;
            if (!in_region) continue;
            for (const auto v : t)
                if (component[v] >= 0) borders_region[static_cast<std::size_t>(component[v])] = 1;
        }
        std::vector<Group> g(count);
        for (std::size_t v = 0; v < n; ++v) {
            if (component[v] < 0 || borders_region[static_cast<std::size_t>(component[v])])
                continue;
            Group& x = g[static_cast<std::size_t>(component[v])];
            x.area += area[v];
            x.centroid += area[v] * reference.positions[v].cast<double>();
            if (std::abs(raw[v]) > std::abs(x.peak)) x.peak = raw[v];
            x.tilt = std::max(x.tilt, static_cast<double>(at.atlas->value_mean[v]));
        }
        for (auto& x : g) {
            if (!(x.area >= d.scale.min_area)) continue;
            ++groups;
            if (x.area > best.area) {
                x.centroid /= x.area;
                best = x;
            }
        }
    }
    if (groups == 0) return std::nullopt;
    char where[160];
    std::snprintf(where, sizeof where, "(%.1f, %.1f, %.1f)", best.centroid.x(), best.centroid.y(),
                  best.centroid.z());
    const std::string why =
        d.normal.corroborates && best.tilt < d.normal.low
            ? "the examined surface's tilt there (at most " + fixed(best.tilt, 1) +
                  "°) stays below the normal floor's lower level " + fixed(d.normal.low, 1) +
                  "°, so the normal field does not corroborate it"
            : "the growth rule or a border's band left less than the smallest detectable area "
              "of it compared, or its peak is shallower than the run can tell there";
    return std::to_string(groups) + " place(s) where the shape change reaches the smallest " +
           "detectable damage hold no region; the largest, " +
           with_unit(best.area, unit, 2, "%.3g") + " around " + where + " " +
           (unit.empty() ? "units" : unit) + " (" + "peak " + with_unit(best.peak, unit) +
           " in the atlas), is not reported because " + why + ": look at the atlas there";
}

std::string own_scale_text(const FusedAtScale& f) {
    std::string t = "the floors at each vertex's own scale are implausible (";
    if (f.normal.implausible) t += "normal: " + f.normal.note;
    if (f.normal.implausible && f.shape.implausible) t += "; ";
    if (f.shape.implausible) t += "shape: " + f.shape.note;
    return t + ")";
}

// The fused rule's regions at one scale: the candidates of the floors `f` measured there over
// the evidence `at` (`d.scale` describes the scale), grown, held to the scale's smallest area and
// to the depth the run can tell at each vertex, described, and their significance stated.
void regions_at_scale(const Mesh& reference, const DecisionEvidence& e, const Coverage& compared,
                      const DecisionOptions& o, const RegionOptions& region_options,
                      const EvidenceAtScale& at, const SamplingBands& bands, const FusedAtScale& f,
                      ZoomDecision& d) {
    const EvidenceScale& s = d.scale;
    RegionFieldStore fields;
    build_fields(e, d.comparison, d.shape.value, fields);
    // A group narrower than the disc the evidence was read over is below what this scale can
    // tell (the smallest detectable area stated above): not a region. Only its compared area
    // counts: surface below resolution or in a border's band is no evidence.
    RegionOptions at_scale = region_options;
    at_scale.min_area = s.min_area;
    at_scale.min_hole_area = std::numbers::pi * s.radius * s.radius;
    std::vector<std::uint8_t> counted;
    if (!d.comparison.vertex_class.empty()) {
        counted.resize(reference.vertex_count());
        for (std::size_t v = 0; v < counted.size(); ++v) counted[v] = d.comparison.compared(v);
        at_scale.min_area_counted = &counted;
    }
    const std::vector<float> limit = depth_limit(reference, e, bands, s);
    at_scale.min_depth = &limit;
    const auto candidates =
        detail::fused_mask(reference, at.evidence, f.excess, d.normal, d.shape, o);
    const auto kept = off_borders(reference, candidates, d);
    d.regions = find_regions(reference, kept, e.coverage->seen, fields.fields, at_scale);
    detail::describe_evidence(d.regions, at.evidence, f.excess, d.normal, d.shape);
    state_significance(reference, compared, at.evidence, f.excess, border_groups(candidates, kept),
                       s.min_area, d);
    for (auto& r : d.regions.regions) {
        r.scale_radius = s.radius;
        if (r.kind != RegionKind::MissingSurface && !r.is_hole_loss() && d.shape.mad > 0)
            r.depth_sd = 1.4826 * d.shape.mad;
    }
}

// The dents and bumps `wider` found that neither overlap nor touch a region of `d` join it
// (each keeps what its own scale measured); then surface gone first, the rest by area, largest
// first, ids in that order (decision/regions.h RegionResult).
void join_wider(const Mesh& reference, const RegionResult& wider, RegionResult& d) {
    const std::size_t n = reference.vertex_count();
    std::vector<std::uint8_t> touches(wider.regions.size() + 1, 0);
    for (const auto& t : reference.triangles) {
        bool finer = false;
        for (const auto v : t) finer = finer || d.region_of_vertex[v] != 0;
        if (!finer) continue;
        for (const auto v : t) touches[static_cast<std::size_t>(wider.region_of_vertex[v])] = 1;
    }
    std::vector<Region> all = d.regions;
    std::vector<std::int32_t> from_wider(wider.regions.size() + 1, 0);  // wider id → index + 1
    for (const auto& r : wider.regions) {
        if (r.kind == RegionKind::MissingSurface || r.is_hole_loss() ||
            touches[static_cast<std::size_t>(r.id)])
            continue;
        all.push_back(r);
        from_wider[static_cast<std::size_t>(r.id)] = static_cast<std::int32_t>(all.size());
    }
    if (all.size() == d.regions.size()) return;
    std::vector<std::size_t> order(all.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (all[a].is_hole_loss() != all[b].is_hole_loss()) return all[a].is_hole_loss();
        return all[a].area > all[b].area;
    });
    std::vector<std::int32_t> new_id(all.size(), 0);  // index → new id
    for (std::size_t k = 0; k < order.size(); ++k)
        new_id[order[k]] = static_cast<std::int32_t>(k + 1);
    for (std::size_t v = 0; v < n; ++v) {
        if (const auto id = d.region_of_vertex[v]; id > 0)
            d.region_of_vertex[v] = new_id[static_cast<std::size_t>(id - 1)];
        else if (const auto w = from_wider[static_cast<std::size_t>(wider.region_of_vertex[v])];
                 w > 0)
            d.region_of_vertex[v] = new_id[static_cast<std::size_t>(w - 1)];
    }
    d.regions.clear();
    for (const std::size_t k : order) {
        d.regions.push_back(all[k]);
        d.regions.back().id = new_id[k];
    }
}

// The search over wider rungs (issue 50, item 1: every position at every scale): the chosen
// radius is the finest where the undamaged majority is quiet, and so the best place for a change
// about that wide; a wider, shallower change stands out only over a wider disc, where the
// majority's spread averages down (the detection limit's curve states how far: on the CBCT jaw
// pair 0.29 mm over 1.6 mm² at the chosen 1.2 mm, 0.16 mm over 6.6 mm² at 2.5 mm). Up to
// kWiderRungs rungs beyond the chosen one are read, each against its own floors, banded, bounded
// and grown as the chosen one; a region they find that no finer region overlaps or touches
// joins the finding (the finer one places a change best: it is where it stood out first). Every
// region's p then counts the scales searched (Bonferroni over scales: conservative, since the
// readings of one pair at neighbouring scales are correlated).
// note: two rungs (2× and 4× the chosen radius), each read sparsely
// (detail::sparse_scaled_evidence): a full reading's cost grows with the disc's vertices, r²
// (the CBCT jaw pair at σ 80 took 75 s instead of 24 s with full readings at 4.9 and 9.8 mm);
// beyond 4× the limit curve flattens (the pair's systematic differences, not its noise, set
// the floor there: 0.159 → 0.154 mm from 2.5 to 4.9 mm on the CBCT jaw).
constexpr std::size_t kWiderRungs = 2;

void search_wider(const Mesh& reference, const DecisionEvidence& e, const Coverage& compared,
                  const DecisionOptions& o, const RegionOptions& region_options,
                  const std::vector<double>& ladder, ZoomDecision& d) {
    // A surface against its mirror image differs by nature, and most over the widest discs (a
    // skull's asymmetry is broad: the CThead condyle-loss pair gained bumps of 187 and 657 mm²
    // at 4.1 and 8.2 mm): the natural floors are read at the chosen scale only.
    if (o.natural_floors) return;
    // Only compared surface is evidence over a wider disc: a thin plate below the scans'
    // resolution, whose two segmentations differ by millimetres, spread over 4 mm into the
    // compared surface around it as a 41 mm² bump 2.2 mm high (CThead's frontal midline, in the
    // unchanged whole-surface pair).
    DecisionEvidence over = e;
    over.coverage = &compared;
    for (const double r : ladder) {
        if (r <= d.scale.radius || d.scale.wider.size() == kWiderRungs) continue;
        d.scale.wider.push_back(r);
        EvidenceAtScale at;
        read_at_scale(reference, over, r, at, true);
        const SamplingBands bands = sampling_bands(at.evidence, compared, at.scaled.distance);
        if (e.sampling) read_in_bands(bands, *e.sampling, at.scaled.distance, at.scaled.tolerance);
        const FusedAtScale f = fused_floors(at.evidence, compared, o, true);
        if (f.normal.implausible || f.shape.implausible) continue;
        ZoomDecision w;
        w.comparison = d.comparison;
        w.normal = f.normal;
        w.shape = f.shape;
        w.scale.radius = r;
        state_detectable(reference, at.evidence, o, w.shape, w.scale);
        regions_at_scale(reference, e, compared, o, region_options, at, bands, f, w);
        for (auto& x : w.regions.regions)
            x.evidence += " over a radius of " + with_unit(r, e.unit) + " (a wider rung)";
        join_wider(reference, w.regions, d.regions);
    }
    const auto scales = static_cast<double>(1 + d.scale.wider.size());
    for (auto& x : d.regions.regions)
        if (std::isfinite(x.p_value)) x.p_value = std::min(1.0, x.p_value * scales);
    if (!d.scale.wider.empty()) {
        std::string radii;
        for (const double r : d.scale.wider)
            radii += (radii.empty() ? "" : ", ") + with_unit(r, e.unit);
        d.rule_text += "; regions were also sought over wider radii (" + radii +
                       "), each against its own floors, a wider region kept where no finer one "
                       "overlaps or touches it; p values count the " +
                       std::to_string(d.scale.wider.size() + 1) + " scales searched";
    }
}

// The fused rule at the first scale where the floors are plausible (decision.h EvidenceScale).
void decide_at_quiet_scale(const Mesh& reference, const DecisionEvidence& e,
                           const Coverage& compared, const DecisionOptions& o,
                           const RegionOptions& region_options, FusedAtScale f, ZoomDecision& d) {
    EvidenceScale& s = d.scale;
    s.searched = true;
    s.quiet = false;
    s.own_normal = f.normal;
    s.own_shape = f.shape;
    const bool implausible = f.normal.implausible || f.shape.implausible;
    // Below a voxel the scans' noise and sampling set the floors, not damage: where the scans
    // have one, loud floors at a vertex's own scale are expected and read past (an unchanged
    // CBCT pair said "more than half of the seen surface differs", which alarms for nothing).
    const bool by_voxel = e.voxel > 0.0;
    const std::string voxel_text = "the scans' voxels reach " + with_unit(e.voxel, e.unit) +
                                   ": the evidence is read no finer than a voxel";
    const std::string own =
        !implausible ? voxel_text
        : by_voxel   ? voxel_text +
                         " (below it, at each vertex's own scale, the scans' noise and "
                         "sampling set floors beyond the plausible)"
                   : own_scale_text(f);
    EvidenceAtScale at;
    SamplingBands bands;
    std::vector<double> ladder = detail::scale_ladder(reference, e.size);
    // note: no rung below the voxel — unless none reaches it (a coarse mesh of a fine scan).
    if (std::any_of(ladder.begin(), ladder.end(), [&](double r) { return r >= e.voxel; }))
        std::erase_if(ladder, [&](double r) { return r < e.voxel; });
    for (const double r : ladder) {
        s.tried.push_back(r);
        read_at_scale(reference, e, r, at);
        bands = sampling_bands(at.evidence, compared, at.scaled.distance);
        if (e.sampling) read_in_bands(bands, *e.sampling, at.scaled.distance, at.scaled.tolerance);
        f = fused_floors(at.evidence, compared, o, true);
        if (f.normal.implausible || f.shape.implausible) continue;
        s.quiet = true;
        s.radius = r;
        break;
    }
    d.normal = f.normal;
    d.shape = f.shape;
    if (!s.quiet) {
        d.regions.region_of_vertex.assign(reference.vertex_count(), 0);
        s.text = "no scale up to a radius of " +
                 with_unit(s.tried.empty() ? 0.0 : s.tried.back(), e.unit) +
                 " makes the undamaged majority quiet: no regions are reported";
        d.rule_text = "fused: " + s.text;
        d.warnings.push_back(own + "; " + s.text +
                             " (the surfaces differ everywhere more than a damage could be told "
                             "from: noise, a poor fit, or surfaces that do not correspond)");
        return;
    }
    d.normal.rule = "median + " + general(o.noise_k) +
                    "·1.4826·MAD of the tilt of the examined surface against the reference over "
                    "a radius of " +
                    with_unit(s.radius, e.unit) +
                    ", over seen vertices with an examined surface, at least " +
                    general(o.min_threshold) + "°";
    state_detectable(reference, at.evidence, o, d.shape, s);
    d.rule_text = fused_rule_text(d, describe(Metric::AngleDeg)) +
                  "; evidence read over a radius of " + with_unit(s.radius, e.unit);
    if (bands.used) {
        // The floors above are in units of the quietest band: where faces lie across the
        // slices the same floor is a deeper change.
        const double across = bands.loudest / bands.quietest;
        s.min_depth_across = s.min_depth * across;
        s.sampling_bands = bands.sigma;
        s.text += " (up to " + with_unit(s.min_depth_across, e.unit) +
                  " deep where faces lie across the grid's thickest slices)";
        d.rule_text +=
            "; the distance is read per band of the grid's staircase step along the normal (" +
            std::to_string(bands.sigma.size()) +
            " bands of equal count, each centred on its median and scaled by its "
            "spread: from " +
            with_unit(bands.quietest, e.unit) + " to " + with_unit(bands.loudest, e.unit) +
            "), so that a face across thick slices, whose staircase is wider, is "
            "judged against surface sampled as it was; floors in units of the "
            "quietest band";
    }
    state_limit_curve(reference, e, compared, o, ladder, s);
    const std::string read =
        own + "; the evidence was read over a radius of " + with_unit(s.radius, e.unit) +
        ", where the undamaged majority is quiet (normal floor " + fixed(d.normal.value, 2) +
        "°, shape floor " + with_unit(d.shape.value, e.unit) +
        "); the smallest detectable damage there: " + with_unit(s.min_depth, e.unit) +
        " deep over " + with_unit(s.min_area, e.unit, 2, "%.3g");
    // A scale chosen for the voxel is no warning: it is how scans are read.
    if (implausible && !by_voxel) d.warnings.push_back(read);
    else s.text = own + "; " + s.text;
    regions_at_scale(reference, e, compared, o, region_options, at, bands, f, d);
    search_wider(reference, e, compared, o, region_options, ladder, d);
    if (auto w =
            unreported_change(reference, compared, at.evidence, f.excess, *e.distance, d, e.unit))
        d.warnings.push_back(*w);
}

void decide_fused(const Mesh& reference, const DecisionEvidence& e, const Coverage& compared,
                  const DecisionOptions& o, const RegionOptions& region_options, ZoomDecision& d) {
    FusedAtScale f = fused_floors(e, compared, o);
    d.normal = f.normal;
    d.shape = f.shape;
    const bool implausible = f.normal.implausible || f.shape.implausible;
    // note: a mesh too coarse for any radius of the ladder (edges beyond 4 % of its size, a
    // cube of 12 triangles) has no scale to move to: its floors are capped and warned about.
    const bool can_scale = !detail::scale_ladder(reference, e.size).empty();
    if (implausible && !can_scale)
        d.warnings.push_back(
            "no smoothing scale fits this mesh (its median edge is longer than "
            "4 % of its size): the implausible floors are capped");
    // note: a hundredth of a voxel. Two scans of one object differ everywhere by partial volume
    // and noise (CThead's volume-edit pair, noise-free: 1.4826·MAD 0.1 mm, 5 % of its 2 mm
    // voxel); a surface derived from the reference (a mesh edit of it) coincides with it on the
    // undamaged majority (MAD 0 on the micro-CT tooth's wear pairs), and there is nothing below
    // a voxel to read past: its own scale stands where it is plausible.
    constexpr double kSampledApartVoxels = 0.01;
    const bool sampled_apart = e.voxel > 0 && 1.4826 * f.shape.mad >= kSampledApartVoxels * e.voxel;
    if ((implausible || sampled_apart) && can_scale && !o.threshold && !o.shape_threshold) {
        if (reference.has_normals()) {
            decide_at_quiet_scale(reference, e, compared, o, region_options, std::move(f), d);
        } else {
            Mesh with_normals = reference;
            compute_vertex_normals(with_normals);
            decide_at_quiet_scale(with_normals, e, compared, o, region_options, std::move(f), d);
        }
        return;
    }
    if (f.normal.implausible) d.warnings.push_back("normal evidence floor: " + f.normal.note);
    if (f.shape.implausible) d.warnings.push_back("shape evidence floor: " + f.shape.note);
    state_detectable(reference, e, o, d.shape, d.scale);
    d.rule_text = fused_rule_text(d, describe(e.metric));
    RegionFieldStore fields;
    build_fields(e, d.comparison, d.shape.value, fields);
    const auto candidates = detail::fused_mask(reference, e, f.excess, d.normal, d.shape, o);
    const auto kept = off_borders(reference, candidates, d);
    d.regions = find_regions(reference, kept, e.coverage->seen, fields.fields, region_options);
    detail::describe_evidence(d.regions, e, f.excess, d.normal, d.shape);
    d.scale.limit_curve.push_back({0.0, d.scale.min_area, d.scale.min_depth, d.scale.min_depth});
    state_significance(reference, compared, e, f.excess, border_groups(candidates, kept),
                       d.scale.min_area, d);
}

// The paper's rule: a seen vertex whose mean normal evidence reaches the floor.
void decide_normal(const Mesh& reference, const DecisionEvidence& e,
                   const RegionOptions& region_options, ZoomDecision& d) {
    const MetricDescriptor& m = describe(e.metric);
    if (d.normal.implausible) d.warnings.push_back("normal evidence floor: " + d.normal.note);
    d.rule_text = "a seen vertex whose per-vertex mean " + std::string(m.name) +
                  " reaches the normal floor " + fixed(d.normal.value, 2) + std::string(m.symbol) +
                  " is damaged; regions are connected groups";
    RegionFieldStore fields;
    build_fields(e, d.comparison, 0.0, fields);
    d.regions = find_regions(reference, off_borders(reference, normal_rule_mask(e, d.normal), d),
                             e.coverage->seen, fields.fields, region_options);
    for (auto& r : d.regions.regions)
        r.evidence = std::string(m.name) + " " + fixed(r.max_value, 2) + std::string(m.symbol) +
                     " ≥ floor " + fixed(d.normal.value, 2) + std::string(m.symbol);
}

// No vertex of the reference is compared (each one unseen, unreached, in a border band or below
// the scans' resolution): the floors would be read over nothing and no damage can be told, so
// none is reported and nothing is stated detectable.
void nothing_compared(const Mesh& reference, ZoomDecision& d) {
    const Comparison& c = d.comparison;
    const auto pct = [&](double a) { return fixed(100.0 * a / c.reference_area, 1) + " %"; };
    d.regions.region_of_vertex.assign(reference.vertex_count(), 0);
    d.scale.min_depth = std::numeric_limits<double>::quiet_NaN();
    d.scale.min_area = std::numeric_limits<double>::quiet_NaN();
    d.scale.text = "nothing of the reference was compared (" + pct(c.not_reached_area) +
                   " not reached by the examined surface, " +
                   pct(c.reference_border_area + c.examined_border_area) + " along borders, " +
                   pct(c.below_resolution_area) +
                   " below the scans' resolution, the rest unseen): no damage can be told";
    d.rule_text = d.scale.text;
    d.warnings.push_back(d.scale.text);
}

}  // namespace

std::string to_string(FloorSource source) {
    switch (source) {
        case FloorSource::Measured: return "measured";
        case FloorSource::Minimum: return "minimum";
        case FloorSource::Capped: return "capped";
        case FloorSource::Given: return "given";
    }
    return "measured";
}

DecisionRule parse_decision_rule(const std::string& text) {
    if (text == "normal") return DecisionRule::Normal;
    if (text == "fused") return DecisionRule::Fused;
    throw InputError("decision rule \"" + text + "\": expected fused or normal");
}

std::string to_string(DecisionRule rule) {
    return rule == DecisionRule::Fused ? "fused" : "normal";
}

void DecisionOptions::validate() const {
    // note: `x > 0 && x < inf` also refuses NaN, which fails every comparison.
    const double inf = std::numeric_limits<double>::infinity();
    if (threshold && !(*threshold > 0 && *threshold < inf))
        throw OptionError("threshold.deg", *threshold, "must be finite and > 0 (metric units)");
    if (!(noise_k > 0 && noise_k < inf))
        throw OptionError("threshold.noise_k", noise_k, "must be finite and > 0");
    if (!(min_threshold >= 0 && min_threshold < inf))
        throw OptionError("threshold.min_deg", min_threshold, "must be finite and ≥ 0");
    // An angle between normals is at most 180°: a larger cap could never be reached.
    if (!(max_plausible_threshold_deg > 0 && max_plausible_threshold_deg <= 180))
        throw OptionError("decision.max_plausible_deg", max_plausible_threshold_deg,
                          "must be in (0, 180] degrees");
    if (resolution && !(*resolution > 0 && *resolution < inf))
        throw OptionError("decision.resolution", *resolution, "must be finite and > 0 mesh units");
    if (shape_threshold && !(*shape_threshold > 0 && *shape_threshold < inf))
        throw OptionError("decision.shape_threshold", *shape_threshold,
                          "must be finite and > 0 mesh units");
    if (!(shape_k > 0 && shape_k < inf))
        throw OptionError("decision.shape_k", shape_k, "must be finite and > 0");
    if (!(shape_low_k > 0 && shape_low_k <= shape_k))
        throw OptionError("decision.shape_low_k", shape_low_k, "must be in (0, shape_k]");
    if (!(min_shape_fraction >= 0))
        throw OptionError("decision.min_shape_fraction", min_shape_fraction, "must be ≥ 0");
    if (!(max_plausible_shape_fraction > 0))
        throw OptionError("decision.max_plausible_shape_fraction", max_plausible_shape_fraction,
                          "must be > 0");
    if (!(grow_fraction > 0 && grow_fraction < 1))
        throw OptionError("decision.grow_fraction", grow_fraction, "must be in (0, 1)");
    if (min_region_vertices < 1)
        throw OptionError("threshold.min_region_vertices", static_cast<double>(min_region_vertices),
                          "must be ≥ 1");
}

Floor robust_floor(const std::vector<float>& values, const std::vector<std::uint8_t>& use, double k,
                   double minimum, double plausible_max) {
    std::vector<float> x;
    x.reserve(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        if (use[i]) x.push_back(values[i]);
    Floor f;
    f.k = k;
    f.minimum = minimum;
    if (x.empty()) {
        f.value = minimum;
        f.source = FloorSource::Minimum;
        return f;
    }
    f.median = median_of(x);
    for (auto& e : x) e = static_cast<float>(std::abs(e - f.median));
    f.mad = median_of(x);
    f.estimate = f.median + k * 1.4826 * f.mad;
    f.value = std::max(f.estimate, minimum);
    f.source = f.estimate < minimum ? FloorSource::Minimum : FloorSource::Measured;
    if (f.value > plausible_max) {
        f.implausible = true;
        f.source = FloorSource::Capped;
        f.value = std::max(plausible_max, minimum);
    }
    return f;
}

ZoomDecision decide(const Mesh& reference, const DecisionEvidence& evidence,
                    const DecisionOptions& o) {
    o.validate();
    GLINT_ASSERT(evidence.atlas && evidence.coverage, "decision without an atlas or coverage");
    ZoomDecision d;
    d.comparison =
        classify_comparison(reference, {.seen = &evidence.coverage->seen,
                                        .missing = &evidence.atlas->missing,
                                        .distance = evidence.distance,
                                        .at_border = evidence.at_border,
                                        .facing_away = evidence.facing_away,
                                        .scan_view = evidence.scan_view,
                                        .below_resolution = evidence.below_resolution,
                                        .beyond_view = evidence.beyond_view,
                                        .examined_encloses = evidence.examined_encloses});
    // Floors and the histogram read the compared vertices; the mask every seen vertex the
    // examined surface reached (a group mostly in a border band is dropped: off_borders).
    Coverage compared = *evidence.coverage;
    Coverage reached = *evidence.coverage;
    for (std::size_t v = 0; v < compared.seen.size(); ++v) {
        compared.seen[v] = compared.seen[v] && d.comparison.compared(v);
        reached.seen[v] =
            reached.seen[v] &&
            d.comparison.vertex_class[v] != static_cast<std::uint8_t>(CompareClass::NotReached);
    }
    DecisionEvidence e = evidence;
    e.coverage = &reached;
    DecisionEvidence over_compared = evidence;
    over_compared.coverage = &compared;
    const MetricDescriptor& m = describe(e.metric);
    d.rule = o.rule;
    d.normal = normal_floor(over_compared, o, m);
    d.histogram = histogram_of(e.atlas->value_mean, compared.seen, m);
    const bool have_distance = e.distance && e.distance->size() == reference.vertex_count();
    const RegionOptions region_options{.min_vertices = o.min_region_vertices,
                                       .fill_holes = o.fill_holes};
    if (o.rule == DecisionRule::Fused && !have_distance) {
        d.rule = DecisionRule::Normal;
        d.warnings.push_back(
            "no shape evidence (signed distance) was measured: the normal rule decided alone");
    }
    if (d.comparison.compared_area <= 0.0 && d.comparison.reference_area > 0.0) {
        nothing_compared(reference, d);
        return d;
    }
    if (d.rule == DecisionRule::Fused) decide_fused(reference, e, compared, o, region_options, d);
    else decide_normal(reference, e, region_options, d);
    // A natural floor is no fault of the run, but the user must know what it leaves out.
    if (o.natural_floors && !d.normal.implausible && !d.normal.note.empty())
        d.warnings.push_back("normal evidence floor: " + d.normal.note);
    return d;
}

std::vector<float> decided_shape(const std::vector<float>& distance, const ZoomDecision& d) {
    if (d.comparison.in_hole.size() != distance.size()) return distance;
    std::vector<float> shape =
        region_shape(distance, d.comparison,
                     gone_depth(d.comparison, d.rule == DecisionRule::Fused ? d.shape.value : 0.0));
    // Where the examined surface never reached, its closest point is whatever surface lies
    // elsewhere (−93 mm across a resected jaw): no shape change is known there.
    const auto& k = d.comparison.vertex_class;
    for (std::size_t v = 0; v < shape.size() && k.size() == shape.size(); ++v)
        if (k[v] == static_cast<std::uint8_t>(CompareClass::NotReached))
            shape[v] = std::numeric_limits<float>::quiet_NaN();
    return shape;
}

}  // namespace glint
