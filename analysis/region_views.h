// Which way to look at a region (issue 51: a close-up of a hatched sheet without its region, a
// "best view" grazing the region so that it is a sliver on the silhouette). A region is best
// seen from where the most of its area faces the viewer unoccluded: its visible projected area,
// Σ over its vertices of dual area × cos(normal, to the viewer), counting a vertex only when the
// ray from it to the viewer leaves the surface. Chosen among the sweep's views (the region's
// best_view: its picture in views/ and report.html) and among directions all round (the
// close-up's direction).
#pragma once

#include "decision/regions.h"
#include "mesh/mesh.h"
#include "mesh/surface_index.h"
#include "scanner/plan.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace glint {

/// Directions tried for a close-up: a spherical Fibonacci set (about 1/64 of the sphere's solid
/// angle each, 14° apart) and the region's mean normal.
inline constexpr int kViewDirections = 64;
/// Vertices of a region each direction is tried with, at most (spread evenly over the region).
inline constexpr std::size_t kViewSamples = 96;

/// Per region of `regions` (region_of_vertex: 1-based ids per reference vertex): best_view
/// becomes the view of zoom `zoom` of `plan` that sees the most of it face on and unoccluded
/// (kept when no view sees any of it), view_direction the direction all round that does, and
/// visible_fraction what share of its area that direction sees projected.
void choose_region_views(const Mesh& reference, const std::shared_ptr<const SurfaceIndex>& index,
                         const SweepPlan& plan, int zoom,
                         const std::vector<std::int32_t>& region_of_vertex,
                         std::vector<Region>& regions);

}  // namespace glint
