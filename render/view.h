// Views: a camera plus the sweep metadata that says where it came from, and the framing
// helpers that place a camera around a mesh at an azimuth / elevation and a zoom.
//
// Zoom (DESIGN.md "footprint averaging"): a footprint is mesh units per pixel at the nearest
// surface of the framed bounding sphere (for orthographic views: everywhere). A distance is
// the camera's distance from the framed centre, mesh units. The paper measured "distance in
// pixels from the camera to the nearest surface element"; ZoomKind::DistancePixels reads
// that pixel as a fixed world length tied to the framed sphere (see there).
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"

#include <string>

namespace glint {

/// A camera and where it came from in a sweep.
struct View {
    Camera camera;
    double azimuth_deg = 0.0;  ///< direction_from_az_el convention (geometry.h)
    double elevation_deg = 0.0;
    /// Mesh units per pixel at the nearest surface of the framed sphere (orthographic: at
    /// every depth). Informative; the camera is what renders.
    double footprint = 0.0;
    int zoom_index = 0;  ///< zoom level within a sweep (0 when not from a sweep)
    int index = 0;       ///< view id within a sweep
};

/// How a zoom is given.
enum class ZoomKind {
    Fit,             ///< frame the whole bounding sphere (value ignored; margin applies)
    Footprint,       ///< value = mesh units per pixel at the nearest surface
    Distance,        ///< value = camera distance from the framed centre, mesh units
    DistancePixels,  ///< value = distance from the camera to the nearest surface of the
                     ///< sphere in pixels of f0 = 2·radius/height (the footprint at which the
                     ///< sphere's diameter spans the image height): distance = radius +
                     ///< value · f0. Perspective only.
};

/// Everything needed to place a camera around a bounding sphere.
struct ViewSpec {
    double azimuth_deg = 0.0;
    double elevation_deg = 0.0;
    ZoomKind zoom = ZoomKind::Fit;
    double zoom_value = 0.0;
    int width = 256;
    int height = 256;
    Projection projection = Projection::Orthographic;
    double fov_y_rad = 0.5;  ///< perspective only
    double margin = 1.05;    ///< ZoomKind::Fit: framed radius = margin × bounding radius
    /// Up hint in world coordinates (+z, as in scanner/plan.h); a fallback axis is used when
    /// the view looks along it.
    Vec3d up{0.0, 0.0, 1.0};
    int zoom_index = 0;
    int index = 0;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

/// Bounding sphere used for framing: centre of the bounding box, half its diagonal.
struct FramingSphere {
    Vec3d center{0.0, 0.0, 0.0};
    double radius = 1.0;
};

/// Bounding sphere of a mesh's bounding box. \throw InputError for an empty mesh.
[[nodiscard]] FramingSphere framing_sphere(const Mesh& mesh);

/// A camera looking at `sphere.center` from direction_from_az_el(az, el).
///
/// Orthographic: the camera sits outside the sphere (distance 2·radius + near margin), and
/// the half height is footprint·height/2. Footprint: given; Fit: 2·margin·radius/min(w, h);
/// Distance d: footprint a perspective camera of the same fov would have at the nearest
/// surface, 2·(d − r)·tan(fov/2)/height.
/// Perspective: Distance: given; Footprint f: d = r + f·height/(2·tan(fov/2));
/// Fit: d = margin·r / sin(fov_min/2) with fov_min the smaller of the two fields of view.
/// near/far planes enclose the sphere.
/// \throw InputError invalid spec (see ViewSpec::validate) or a distance inside the sphere.
[[nodiscard]] View make_view(const FramingSphere& sphere, const ViewSpec& spec);

/// make_view around the mesh's framing sphere.
[[nodiscard]] View make_view(const Mesh& mesh, const ViewSpec& spec);

/// "ortho" / "orthographic" / "perspective". \throw InputError.
[[nodiscard]] Projection parse_projection(const std::string& text);

}  // namespace glint
