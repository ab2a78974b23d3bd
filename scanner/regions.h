// Damaged vertices grouped into connected regions over the reference mesh.
#pragma once

#include "mesh/mesh.h"

#include <cstdint>
#include <string>
#include <vector>

namespace glint {

enum class RegionKind { Dent, Bump };

struct Region {
    std::int32_t id = 0;            ///< 1-based; 0 in region_of_vertex means none
    std::size_t vertex_count = 0;
    double area = 0.0;              ///< mesh units², sum of the vertices' dual areas
    double max_angle_deg = 0.0;
    double mean_angle_deg = 0.0;    ///< area-weighted
    double max_depth = 0.0;         ///< per-vertex mean signed depth difference of largest magnitude
    double max_distance = 0.0;      ///< signed surface distance of largest magnitude
    Vec3d centroid{0, 0, 0};        ///< area-weighted, reference coordinates
    std::int32_t best_view = -1;    ///< view where the region's strongest deviation was seen
    RegionKind kind = RegionKind::Dent;
};

/// Inputs per reference vertex (all arrays one value per vertex).
struct RegionInputs {
    const std::vector<float>* angle_deg = nullptr;      ///< deviation used for the threshold
    const std::vector<float>* depth = nullptr;          ///< mean signed depth (optional; NaN = none)
    const std::vector<float>* distance = nullptr;       ///< signed distance (optional)
    const std::vector<std::int32_t>* view = nullptr;    ///< view of the max (optional)
    const std::vector<std::uint8_t>* seen = nullptr;    ///< 1 = observed
};

struct RegionOptions {
    double threshold_deg = 5.0;       ///< a seen vertex with angle ≥ threshold is damaged
    std::size_t min_vertices = 3;     ///< smaller groups are dropped (counted in dropped)
    /// Fill holes: a group of undamaged seen vertices enclosed by one region and smaller than
    /// it joins that region. The floor of a dent keeps its normal (its tilt is zero at the
    /// deepest point), so the angle marks a ring; the ring's inside is damaged too.
    bool fill_holes = true;
};

struct RegionResult {
    std::vector<Region> regions;             ///< sorted by area, largest first; ids follow
    std::vector<std::int32_t> region_of_vertex;
    std::size_t damaged_vertices = 0;
    std::size_t dropped_small = 0;           ///< groups below min_vertices
    std::size_t filled_vertices = 0;         ///< vertices added by hole filling
};

/// Connected components (through mesh edges) of damaged vertices, with their statistics.
/// Sign (dent/bump): the sign of the area-weighted mean signed distance when given, else of
/// the signed depth.
[[nodiscard]] RegionResult find_regions(const Mesh& mesh, const RegionInputs& in,
                                        const RegionOptions& options);

[[nodiscard]] std::string to_string(RegionKind kind);

}  // namespace glint
