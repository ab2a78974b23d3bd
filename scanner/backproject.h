// Back-projection: one view's per-pixel deviations folded onto the reference vertices.
//
// Scatter: a covered reference pixel shows one reference triangle (its primitive id); the
//   ray through the pixel centre meets that triangle's plane at barycentric weights that
//   spread the pixel's value over the triangle's three vertices (AtlasAccumulator::add).
// Gather: at a coarse footprint one pixel covers many small triangles, and most vertices are
//   on no pixel's centre triangle. Each visible vertex that no pixel centre fell on reads the
//   (footprint-averaged) deviation of the pixel it projects to. Visible: it projects onto a
//   fully covered pixel whose depth is within the pixel's own depth spread (3 footprints, or
//   2 % of the framed radius), and its normal faces the camera within the incidence limit.
//
// Coverage rule (both passes): an observation counts only when the surface's front faces the
// camera at an incidence of at most max_incidence (signed: the back of an open surface, seen
// from behind or through a hole, is no observation of it).
#pragma once

#include "mesh/mesh.h"
#include "render/frame.h"
#include "render/view.h"
#include "scanner/atlas.h"
#include "scanner/compare.h"

#include <cstdint>
#include <vector>

namespace glint {

struct BackprojectOptions {
    double min_cos_incidence = 0.2588;  ///< cos of the largest incidence angle (75°)
    float min_coverage = 0.999f;        ///< a reference pixel must be this covered (CompareOptions)
    float missing_value = 90.0f;        ///< value of a pixel with no examined surface (metric)
    double framed_radius = 1.0;         ///< of the sweep plan (depth tolerance of the gather pass)
};

/// Scratch space reused across views (one per accumulator).
struct BackprojectScratch {
    std::vector<std::int32_t> scattered_in;  ///< per vertex: last view whose scatter reached it
};

/// Folds the view into `atlas`; returns the number of covered reference pixels.
/// `deviation.value` holds the metric per pixel. \pre the reference has vertex normals.
std::size_t backproject_view(const Mesh& reference, const View& view, const Frame& reference_frame,
                             const DeviationMap& deviation, const BackprojectOptions& options,
                             AtlasAccumulator& atlas, BackprojectScratch& scratch);

}  // namespace glint
