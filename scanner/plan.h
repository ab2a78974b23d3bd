// Sweep plans: which views the virtual rotary scanner takes.
//
// Rotary: azimuth steps × elevation rings × zoom levels (the paper's rotary scan).
// Sphere: N near-uniform directions on a Fibonacci sphere × zoom levels.
// Either can be restricted to a region of interest (ROI): views are framed on the ROI and
// only directions from which the ROI is visible (some ROI vertex normal faces the camera)
// are kept.
//
// Framing: orthographic cameras looking at the centre of the framed sphere (the bounding
// sphere of the mesh or of the ROI). A zoom level is a footprint (mesh units per pixel);
// the image size of that level is what frames the sphere at that footprint, so a finer
// zoom costs more pixels, never less surface. Up is +z unless the view looks along z.
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "mesh/roi.h"
#include "render/view.h"

#include <optional>
#include <string>
#include <vector>

namespace glint {

struct SweepPlanOptions {
    enum class Kind { Rotary, Sphere } kind = Kind::Rotary;
    double azimuth_step_deg = 30.0;                           ///< rotary: 0 < step ≤ 360
    std::vector<double> elevations_deg{-60, -30, 0, 30, 60};  ///< rotary: each in [-90, 90]
    int sphere_views = 64;                                    ///< sphere: N ≥ 1
    /// Footprints in mesh units per pixel, finest first is not required. Empty: one level
    /// framing the sphere in `size` pixels.
    std::vector<double> footprints;
    int size = 256;        ///< image size (square) of the level framing the whole sphere
    int max_size = 4096;   ///< larger images are refused (choose an ROI or a coarser zoom)
    double margin = 1.05;  ///< framed radius = margin × bounding radius
    /// Analyse only this part of the reference (mesh/roi.h); a vertex mask must be read.
    std::optional<Roi> roi;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

/// One view of the plan.
struct PlannedView {
    View view;     ///< camera, azimuth / elevation, footprint, zoom and view index
    int ring = 0;  ///< rotary: elevation ring index (mosaic row); sphere: 0
    int step = 0;  ///< rotary: azimuth step (mosaic column); sphere: the view id
};

struct SweepPlan {
    SweepPlanOptions options;
    Vec3d target{0, 0, 0};           ///< framed sphere centre
    double radius = 0.0;             ///< framed sphere radius (with margin)
    std::vector<double> footprints;  ///< per zoom level, as used
    std::vector<int> sizes;          ///< image size per zoom level
    std::vector<PlannedView> views;
    int columns = 1;               ///< mosaic layout (rotary: azimuth steps)
    int rows = 1;                  ///< mosaic layout (rotary: elevation rings)
    std::size_t roi_vertices = 0;  ///< vertices inside the ROI (0 without ROI)
};

/// Builds the plan for a reference mesh (normals required for ROI visibility).
/// \throw InputError invalid options, an ROI containing no vertex, an image too large.
[[nodiscard]] SweepPlan make_sweep_plan(const Mesh& reference, const SweepPlanOptions& options);

/// Parses "rotary" or "sphere:N" into options.kind / sphere_views. \throw InputError.
void parse_plan_kind(const std::string& text, SweepPlanOptions& options);

}  // namespace glint
