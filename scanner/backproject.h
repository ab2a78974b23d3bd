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
//
// Streaming (scanner/sweep.cpp): the scatter runs on each band of rows as it is rendered, on
// the worker that rendered it (scatter_rows: the band's samples, in pixel order); once the view
// is whole, fold_view adds them to the atlas and gathers. The fold splits the vertices into
// ranges, one per worker: a vertex receives its observations in the order one thread going
// through the pixels, then the vertices, would give them, so the atlas is the same bit for bit
// whatever the number of workers.
#pragma once

#include "mesh/mesh.h"
#include "render/frame.h"
#include "render/view.h"
#include "scanner/atlas.h"
#include "scanner/compare.h"

#include <cstdint>
#include <span>
#include <vector>

namespace glint {

struct BackprojectOptions {
    double min_cos_incidence = 0.2588;  ///< cos of the largest incidence angle (75°)
    float min_coverage = 0.999f;        ///< a reference pixel must be this covered (CompareOptions)
    float missing_value = 90.0f;        ///< value of a pixel with no examined surface (metric)
    double framed_radius = 1.0;         ///< of the sweep plan (depth tolerance of the gather pass)
};

/// What the back-projection reads of one view, per pixel: the comparison, and the reference
/// frame's depth and full coverage (the gather's visibility test). Reused across views.
struct ViewMaps {
    DeviationMap deviation;                       ///< value (the metric), signed depth, silhouette
    std::vector<float> reference_depth;           ///< linear depth of the reference pixel
    std::vector<std::uint8_t> reference_covered;  ///< 1: a primitive and at least min_coverage

    /// Sizes every map for a width × height view.
    void resize(int width, int height);
};

/// Records the reference rows' depth and coverage into `maps` (rows at their place in the view).
void record_reference_rows(const FrameRows& reference, float min_coverage, ViewMaps& maps);

/// The scatter samples of a band of reference rows (pixel order), appended to `samples`;
/// `maps.deviation` must hold the band's values. Returns the band's covered reference pixels.
std::size_t scatter_rows(const Mesh& reference, const View& view, const FrameRows& reference_rows,
                         const ViewMaps& maps, const BackprojectOptions& options,
                         std::vector<AtlasSample>& samples);

/// Scratch space reused across views (one per accumulator).
struct BackprojectScratch {
    std::vector<std::int32_t> scattered_in;  ///< per vertex: last view whose scatter reached it
};

/// Adds a view's scatter samples (`bands` in pixel order) to the atlas, then gathers the
/// vertices no sample reached, on up to `threads` workers (0 = the machine's).
/// \pre the reference has vertex normals; maps filled for the whole view.
void fold_view(const Mesh& reference, const View& view,
               std::span<const std::vector<AtlasSample>* const> bands, const ViewMaps& maps,
               const BackprojectOptions& options, AtlasAccumulator& atlas,
               BackprojectScratch& scratch, int threads);

}  // namespace glint
