// Pictures people read (issues 14, 26): every image a sweep writes shows the reference surface
// shaded, a signed depth on a diverging map with a symmetric scale in mesh units (blue = loss,
// white = none, red = gain), regions outlined and numbered with the ids of regions.csv /
// report.json, and a legend with the unit, the floors and the regions:
//
//   views/z<k>_az<A>_el<E>.png   each view of the sweep (ExportOptions::write_views): what that
//                                view measured (report/view_measurements.h): its signed depth
//                                along the ray, paler within the zoom's floor; reference surface
//                                with no examined surface behind it hatched violet, examined
//                                surface beyond the reference outline green, the rest not
//                                compared hatched; the title gives the share beyond the floor
//   mosaic_z<k>.png              zoom k's summary: a chart of azimuth × elevation, each view's
//                                share of compared pixels beyond the floor (the regions' best
//                                views framed with their ids), and below it the views that saw
//                                the regions (and those that measured most) drawn whole at
//                                ExportOptions::mosaic_tile pixels
//   atlas.png                    the atlas (zoom 0) from six directions along the axes, unseen
//                                parts hatched
//
// Without a view's measurement (a sweep that compared on the GPU sends no pixels back) its
// picture shows the atlas from that view and says so in its title.
//
// Every view panel, close-up and per-view picture carries a scale bar in the mesh unit
// (report/detail/scale_bar.h); atlas.png a footer naming both inputs, the date, the fit and the
// floors with their sources (report/detail/footer.h), so a picture cited alone says what it
// shows. Text is UTF-8 ("°", "²", "−"); region numbers keep off each other and off captions
// (report/detail/labels.h); a missing-surface region is given its area, no depth.
//
// Every picture draws the orientation's up up (report/orientation.h): superior for a surface
// in a patient space, else +z or what --up says; the sweep's views are only rolled for it.
//
// They are drawn after the decision (regions are known only then) from the reference: its
// frames are rendered again on the CPU (Embree, render/renderer.h, one ray per pixel),
// per-pixel values come from the frame's primitive ids (report/detail/surface_paint.h) or,
// for a view's own measurement, from its grid (report/detail/measured_pixels.h).
// Pictures are rendered at the size they are shown (mosaic tiles at the tile size), so nothing
// full-size is resized.
#pragma once

#include "analysis/analysis.h"
#include "mesh/mesh.h"
#include "render/view.h"
#include "report/export_options.h"
#include "report/orientation.h"
#include "report/output_folder.h"
#include "report/view_measurements.h"

#include <map>
#include <string>
#include <vector>

namespace glint {

/// The colour range of the signed shape change every picture and the atlas colours use.
struct ShapeScale {
    double limit = 1.0;  ///< colour range ±limit, mesh units (> 0)
    std::string source;  ///< how it was chosen, for the legend
    double floor = 0.0;  ///< zoom 0's shape floor (0 when the rule has none)
};

/// The range: the median |peak depth| of zoom 0's dent and bump regions (the peak of a single
/// region), else the 99th percentile of |distance| over seen vertices; at least twice the
/// shape floor (so noise stays pale); rounded up to 1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 × 10^k.
[[nodiscard]] ShapeScale shape_scale(const AnalysisResult& result);

/// File name stem of a view's pictures and numbers: "z0_az030.0_el+30.0".
[[nodiscard]] std::string view_file_stem(const View& view);

/// What the report page embeds.
struct PictureOutput {
    std::map<int, std::string> best_views;  ///< PNG bytes of the regions' best views, by view index
    std::vector<std::string> mosaics;       ///< PNG bytes of mosaic_z<k>.png, per zoom
    std::string atlas;                      ///< PNG bytes of atlas.png (empty: none drawn)
};

/// Best views kept for the report page, at most (the largest regions' first).
inline constexpr std::size_t kMaxBestViews = 24;

/// What atlas.png's title and footer name (the footer also holds the fit and the floors).
struct PictureCaption {
    std::string reference_name;  ///< the file name, or "" ("the reference")
    std::string examined_name;   ///< the file name, or ""
    std::string date;            ///< of the run; "" → the time the pictures are drawn (UTC)
};

/// Writes the pictures above into the folder, drawn with `orientation`'s up up and its
/// directions' names; `caption` titles atlas.png and fills its footer; `measured` holds what
/// each view measured (null, or a view missing: that view is drawn from the atlas). `observer` hears items
/// for each per-view picture (in the stage its caller announced), then the stages "mosaics"
/// (items: each zoom) and "atlas.png".
/// \throw IoError, DeviceError (rendering).
[[nodiscard]] PictureOutput write_pictures(const OutputFolder& folder, const Mesh& reference,
                                           const AnalysisResult& result,
                                           const ExportOptions& options,
                                           const Orientation& orientation,
                                           const PictureCaption& caption = {},
                                           const AnalysisObserver& observer = {},
                                           const ViewMeasurements* measured = nullptr);

}  // namespace glint
