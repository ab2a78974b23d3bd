// A view's measurement (report/view_measurements.h) drawn in its pictures (private to
// report/): the grid kept during the sweep, in the sweep camera's image, mapped onto a picture
// of the same view rendered at another size and rolled upright (report/orientation.h), and the
// test that says whether a cell measured beyond the zoom's floors.
#pragma once

#include "render/view.h"
#include "report/detail/surface_paint.h"
#include "report/view_measurements.h"

namespace glint::detail {

/// The floors a view's cell is held against.
struct MeasuredFloor {
    double normal = 0.0;  ///< the sweep's metric (degrees for the angle): the zoom's normal floor
    double depth = 0.0;   ///< |signed depth|, mesh units (0: not used): view_depth_floor()
};

/// The view's own floor of |signed depth|: median + k·1.4826·MAD of its compared cells'
/// |depth|, at least `least` (the zoom's shape floor, or the level at which two tessellations
/// lie apart, when larger). note: the zoom's shape floor holds the per-vertex distance, whose
/// tessellation tolerance is known per vertex; a pixel's depth differs between two
/// tessellations by their chords' sag, everywhere, and between two scans by their noise, so
/// each view also measures its own level from its undamaged majority (DESIGN.md "scale from
/// the noise").
[[nodiscard]] double view_depth_floor(const ViewMeasurement& measured, double least, double k);

/// Whether a compared cell measured beyond the floor: with a depth floor (the fused rule, whose
/// regions rest on shape evidence) its |signed depth| above it, else its metric above the
/// normal floor. note: not the metric under the fused rule: two tessellations of a curved
/// surface (a tooth's cusps) differ in normal by more than the normal floor at many pixels
/// where they differ in depth by nothing a picture can show.
[[nodiscard]] bool beyond_floor(float depth, float value, const MeasuredFloor& floor);

/// The measurement per pixel of a picture of `shown` (the sweep's `measured_view` resized and
/// rolled: the same eye and axis): each picture pixel's ray projected into the sweep camera
/// picks its grid cell (nearest). Pixels outside the sweep's image measure nothing.
[[nodiscard]] MeasuredPixels measured_pixels(const ViewMeasurement& measured,
                                             const View& measured_view, const View& shown,
                                             const MeasuredFloor& floor);

}  // namespace glint::detail
