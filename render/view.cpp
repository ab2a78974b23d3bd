#include "render/view.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace glint {

namespace {

std::string field_error(const char* field, double value, const char* rule) {
    std::ostringstream s;
    s << "view: " << field << " = " << value << ", expected " << rule;
    return s.str();
}

// note: no view frames the mesh smaller than a millionth of the image or sees it from a
// million framing radii away; beyond that Embree's BVH aborts on the rays' coordinates
// (1e30 footprints and distances, issue 23) and no picture would show anything.
constexpr double kMaxFramedRadii = 1e6;

const char* zoom_name(ZoomKind zoom) {
    switch (zoom) {
        case ZoomKind::Footprint: return "footprint";
        case ZoomKind::Distance: return "distance";
        case ZoomKind::DistancePixels: return "distance_px";
        case ZoomKind::Fit: break;
    }
    return "margin";
}

// The view's extent (orthographic half height, perspective distance) against the mesh's size.
void check_plausible(const ViewSpec& spec, double extent, double r) {
    if (extent <= kMaxFramedRadii * r) return;
    std::ostringstream rule;
    rule << "a view within 1e6 framing radii (radius " << r << "): the image spans "
         << (spec.projection == Projection::Orthographic ? 2.0 * extent : extent)
         << (spec.projection == Projection::Orthographic ? " across" : " from the mesh");
    const std::string text = rule.str();
    throw InputError(field_error(zoom_name(spec.zoom),
                                 spec.zoom == ZoomKind::Fit ? spec.margin : spec.zoom_value,
                                 text.c_str()));
}

}  // namespace

void ViewSpec::validate() const {
    // note: 16384 is the largest image dimension glint renders (Vulkan's
    // maxImageDimension2D is ≥ 4096 everywhere, 16384 on lavapipe and desktop GPUs).
    if (width < 1 || width > 16384) throw InputError(field_error("width", width, "1..16384"));
    if (height < 1 || height > 16384) throw InputError(field_error("height", height, "1..16384"));
    // note: ten turns either way is more than any plan or view file needs; beyond it the angle in
    // radians loses its fraction, and at 1e308 it overflowed to inf, the camera to NaN and
    // Embree aborted (issue 52).
    if (!(std::abs(azimuth_deg) <= 3600.0))
        throw InputError(field_error("azimuth_deg", azimuth_deg, "-3600..3600 degrees"));
    if (!std::isfinite(elevation_deg) || elevation_deg < -90.0 || elevation_deg > 90.0) {
        throw InputError(field_error("elevation_deg", elevation_deg, "-90..90"));
    }
    if (projection == Projection::Perspective && !(fov_y_rad > 0.0 && fov_y_rad < 3.1)) {
        throw InputError(field_error("fov_y_rad", fov_y_rad, "0 < fov < 3.1 rad"));
    }
    if (zoom != ZoomKind::Fit && !(zoom_value > 0.0 && std::isfinite(zoom_value))) {
        throw InputError(field_error("zoom_value", zoom_value, "> 0 (footprint or distance)"));
    }
    if (zoom == ZoomKind::Fit && !(margin > 0.0 && std::isfinite(margin))) {
        throw InputError(field_error("margin", margin, "> 0"));
    }
    if (zoom == ZoomKind::DistancePixels && projection != Projection::Perspective) {
        throw InputError(
            "view: zoom in pixels of distance needs a perspective projection "
            "(an orthographic camera's footprint does not depend on distance)");
    }
    if (!(up.norm() > 0.0)) throw InputError("view: up vector is zero");
}

FramingSphere framing_sphere(const Mesh& mesh) {
    if (mesh.positions.empty()) throw InputError("framing: mesh has no vertices");
    const Bounds b = bounds(mesh);
    FramingSphere sphere;
    sphere.center = b.center().cast<double>();
    // note: a single point has radius 0; 1e-6 of a unit keeps the camera maths finite.
    sphere.radius = std::max(0.5 * static_cast<double>(b.diagonal()), 1e-6);
    return sphere;
}

View make_view(const FramingSphere& sphere, const ViewSpec& spec) {
    spec.validate();
    const double r = sphere.radius;
    View view;
    view.azimuth_deg = spec.azimuth_deg;
    view.elevation_deg = spec.elevation_deg;
    view.zoom_index = spec.zoom_index;
    view.index = spec.index;
    Camera& cam = view.camera;
    cam.width = spec.width;
    cam.height = spec.height;
    cam.projection = spec.projection;
    cam.fov_y_rad = spec.fov_y_rad;
    const Vec3d dir = direction_from_az_el(spec.azimuth_deg, spec.elevation_deg);
    const double tan_half = std::tan(0.5 * spec.fov_y_rad);
    const double aspect = static_cast<double>(spec.width) / spec.height;

    double distance = 0.0;
    if (spec.projection == Projection::Orthographic) {
        double footprint = 0.0;
        switch (spec.zoom) {
            case ZoomKind::Fit:
                footprint = 2.0 * spec.margin * r / std::min(spec.width, spec.height);
                break;
            case ZoomKind::Footprint: footprint = spec.zoom_value; break;
            case ZoomKind::Distance:
                if (spec.zoom_value <= r) {
                    throw InputError(field_error("distance", spec.zoom_value,
                                                 "> the framed radius (camera outside the mesh)"));
                }
                footprint = 2.0 * (spec.zoom_value - r) * tan_half / spec.height;
                break;
            case ZoomKind::DistancePixels: break;  // rejected by validate()
        }
        cam.ortho_half_height = 0.5 * footprint * spec.height;
        check_plausible(spec, cam.ortho_half_height, r);
        // The camera sits outside the sphere; the image plane is at the eye, so the near
        // plane can be tiny.
        distance = 2.0 * r;
        cam.near_plane = 0.01 * r;
        cam.far_plane = distance + 2.0 * r;
        view.footprint = footprint;
    } else {
        switch (spec.zoom) {
            case ZoomKind::Fit: {
                const double tan_min = std::min(tan_half, tan_half * aspect);
                distance = spec.margin * r / std::sin(std::atan(tan_min));
                break;
            }
            case ZoomKind::Footprint:
                distance = r + spec.zoom_value * spec.height / (2.0 * tan_half);
                break;
            case ZoomKind::Distance: distance = spec.zoom_value; break;
            case ZoomKind::DistancePixels: {
                // The paper's pixel unit, fixed per mesh: f0 = 2r/h (view.h).
                const double f0 = 2.0 * r / spec.height;
                distance = r + spec.zoom_value * f0;
                break;
            }
        }
        check_plausible(spec, distance, r);
        if (distance <= r) {
            throw InputError(
                field_error("distance", distance, "> the framed radius (camera outside the mesh)"));
        }
        cam.near_plane = std::max(distance - r, 1e-3 * r) * 0.5;
        cam.far_plane = distance + 2.0 * r;
        view.footprint = cam.footprint_at(distance - r);
    }
    const Vec3d eye = sphere.center + distance * dir;
    cam.world_from_camera = look_at(eye, sphere.center, spec.up);
    return view;
}

View make_view(const Mesh& mesh, const ViewSpec& spec) {
    return make_view(framing_sphere(mesh), spec);
}

Projection parse_projection(const std::string& text) {
    if (text == "ortho" || text == "orthographic") return Projection::Orthographic;
    if (text == "perspective" || text == "persp") return Projection::Perspective;
    throw InputError("projection \"" + text + "\": expected orthographic or perspective");
}

}  // namespace glint
