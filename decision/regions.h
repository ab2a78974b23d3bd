// Damaged vertices grouped into connected regions over the reference mesh, and measured.
#pragma once

#include "mesh/mesh.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace glint {

enum class RegionKind {
    Dent,  ///< loss: the examined surface lies inside the reference (negative shape change)
    Bump,  ///< gain: the examined surface lies outside (positive shape change)
    MissingSurface,  ///< the examined mesh has no surface there (a hole, a cut, an unscanned part)
};

struct Region {
    std::int32_t id = 0;  ///< 1-based; 0 in region_of_vertex means none
    std::size_t vertex_count = 0;
    double area = 0.0;        ///< mesh units², sum of the vertices' dual areas
    double max_value = 0.0;   ///< the metric's largest per-vertex mean in the region
    double mean_value = 0.0;  ///< the metric, area-weighted mean
    double peak_depth = 0.0;  ///< signed shape change of largest magnitude (mesh units; neg = loss)
    double mean_depth = 0.0;  ///< area-weighted mean signed shape change (mesh units)
    /// Σ area·shape change (mesh units³; neg = volume lost); for surface gone
    /// (is_hole_loss) the solid it bounds with the surface across its rim.
    double volume = 0.0;
    double missing_fraction = 0.0;  ///< area share whose observations found no examined surface
    Vec3d centroid{0, 0, 0};        ///< area-weighted, reference coordinates
    /// The sweep view that sees the most of the region face on and unoccluded
    /// (analysis/region_views.h); before that choice, the view of its strongest deviation.
    std::int32_t best_view = -1;
    /// The direction (unit, from the region towards the viewer) that sees the most of it face on
    /// and unoccluded, and the share of its area seen projected from there (0: not chosen).
    Vec3d view_direction{0, 0, 0};
    double visible_fraction = 0.0;
    RegionKind kind = RegionKind::Dent;
    /// The region lies mostly in a hole (RegionFields::gone): the examined surface holds none
    /// there, and a dent's depth is what the reference stood above the hole's rim, a lower
    /// bound of the loss.
    bool hole = false;
    std::string evidence;  ///< why the decision admitted it (filled by decision/decision.cpp)
    /// How strongly it stands out from the undamaged surface (decision/decision.h Significance;
    /// filled by the fused rule, NaN otherwise): its strongest shape excess in robust standard
    /// deviations of the distance on the compared surface, at the scale the evidence was read.
    double z = std::numeric_limits<double>::quiet_NaN();
    /// The family-wise chance of a change this strong anywhere on the undamaged surface: the
    /// larger of the Gaussian bound over every resolution element searched and the share of
    /// the compared surface outside all regions that stands as high, per resolution element.
    double p_value = std::numeric_limits<double>::quiet_NaN();
    /// The radius the evidence that found it was read over (decision/decision.h EvidenceScale;
    /// 0: each vertex's own). A change wider than the scale the undamaged majority is quiet at
    /// may stand out only over a wider disc, where the spread averages down.
    double scale_radius = 0.0;
    /// One robust standard deviation of the distance on the undamaged surface at that scale
    /// (mesh units; NaN: not measured): the ± of its depth.
    double depth_sd = std::numeric_limits<double>::quiet_NaN();

    /// Surface gone in a hole: a loss whose depth is a lower bound (`hole` above).
    [[nodiscard]] bool is_hole_loss() const { return kind == RegionKind::Dent && hole; }
};

/// Per reference vertex fields the statistics read (each one value per vertex; optional
/// ones may be null).
struct RegionFields {
    const std::vector<float>* value = nullptr;  ///< the metric's per-vertex mean (required)
    const std::vector<float>* shape = nullptr;  ///< signed shape change (mesh units; NaN = unknown)
    const std::vector<float>* missing =
        nullptr;  ///< share of observations without examined surface
    const std::vector<std::int32_t>* view = nullptr;  ///< view of the vertex's maximum
    /// Depth of the surface gone in a hole (decision/comparison.h): negative = a measurable
    /// loss, 0 = a hole whose loss is not measurable, NaN = no hole. A region mostly in a hole
    /// is a dent when the hole lost measurable surface, else "missing surface".
    const std::vector<float>* gone = nullptr;
    /// 1: the vertex's hole is a loss whatever its measured depth (Comparison::hole_loss: the
    /// examined surface cannot drop out). A region mostly in such holes is a dent, its depth a
    /// lower bound. May be null.
    const std::vector<std::uint8_t>* gone_loss = nullptr;
};

struct RegionOptions {
    std::size_t min_vertices = 3;  ///< smaller groups are dropped (counted in dropped_small)
    /// Groups of a smaller area are dropped too (counted in dropped_small): at a smoothing
    /// scale of radius r the evidence cannot resolve damage narrower than one resolution
    /// element of it (decision.cpp resolution_element_area).
    double min_area = 0.0;
    /// When set (per vertex, 1: counted), min_area is met by the area of these vertices only:
    /// the compared ones. Surface below the scans' resolution or in a border's band is no
    /// evidence, and a group is not told apart by area it could not compare.
    const std::vector<std::uint8_t>* min_area_counted = nullptr;
    /// Surface gone (Region::is_hole_loss) smaller than this is dropped too (counted in
    /// dropped_small): a hole of the examined surface narrower than the whole disc the evidence
    /// is read over (π·r², wider than min_area's resolution element) is where one segmentation
    /// dropped out (noise opening thin bone), no loss the run can tell; its depth is only the
    /// height above the rim, no smoothed evidence.
    double min_hole_area = 0.0;
    /// Per vertex, the smallest depth the run can tell there (mesh units; may be null): a group
    /// whose peak shape change is shallower than the limit at its peak's vertex is dropped
    /// (counted in dropped_shallow): the run states it cannot tell such a change. Missing
    /// surface has no depth and is never dropped by it.
    const std::vector<float>* min_depth = nullptr;
    /// Fill holes: a group of undamaged seen vertices enclosed by one region and smaller than
    /// it joins that region. The floor of a dent keeps its normal (its tilt is zero at the
    /// deepest point), so normal evidence marks a ring; the ring's inside is damaged too.
    bool fill_holes = true;
    /// A region whose observations found no examined surface on more than this share of its
    /// area is MissingSurface, whatever the sign of its shape change.
    double missing_majority = 0.5;
};

struct RegionResult {
    /// Surface gone first (is_hole_loss), then by area, largest first; ids follow.
    std::vector<Region> regions;
    std::vector<std::int32_t> region_of_vertex;
    std::size_t damaged_vertices = 0;  ///< in the mask given (before filling and dropping)
    std::size_t dropped_small = 0;     ///< groups below min_vertices
    std::size_t dropped_shallow = 0;   ///< groups shallower than RegionOptions::min_depth
    std::size_t filled_vertices = 0;   ///< vertices added by hole filling
};

/// Connected components (through mesh edges) of the damaged vertices (`damaged[v]` != 0,
/// only seen ones count), with their statistics. Kind: MissingSurface by majority (see
/// RegionOptions), else the sign of the peak shape change, so a region's kind never
/// contradicts its reported depth.
[[nodiscard]] RegionResult find_regions(const Mesh& mesh, std::vector<std::uint8_t> damaged,
                                        const std::vector<std::uint8_t>& seen,
                                        const RegionFields& fields,
                                        const RegionOptions& options = {});

/// "dent", "bump", "missing surface".
[[nodiscard]] std::string to_string(RegionKind kind);

}  // namespace glint
