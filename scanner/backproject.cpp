#include "scanner/backproject.h"

#include "mesh/error.h"
#include "mesh/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Barycentric weights of the point where `ray` meets the plane of triangle t, clamped to the
// triangle (the pixel centre may fall just outside the triangle its sub-sample hit).
// cos_incidence is signed: positive when the triangle's front (its winding's normal, the side
// its vertex normals point to) faces the camera.
bool barycentric(const Mesh& mesh, std::uint32_t t, const Ray& ray, std::array<float, 3>& w, double& cos_incidence) {
    const auto& tri = mesh.triangles[t];
    const Vec3d a = mesh.positions[tri[0]].cast<double>();
    const Vec3d b = mesh.positions[tri[1]].cast<double>();
    const Vec3d c = mesh.positions[tri[2]].cast<double>();
    const Vec3d n = (b - a).cross(c - a);
    const double area2 = n.norm();
    if (!(area2 > 0)) return false;
    const double denom = n.dot(ray.direction);
    cos_incidence = -denom / area2;
    if (std::abs(denom) < 1e-12 * area2) return false;
    const double s = n.dot(a - ray.origin) / denom;
    const Vec3d p = ray.origin + s * ray.direction;
    const double ua = n.dot((b - p).cross(c - p)) / (area2 * area2);
    const double ub = n.dot((c - p).cross(a - p)) / (area2 * area2);
    const double wa = std::max(0.0, ua);
    const double wb = std::max(0.0, ub);
    const double wc = std::max(0.0, 1.0 - ua - ub);
    const double sum = wa + wb + wc;
    if (!(sum > 0)) return false;
    w = {static_cast<float>(wa / sum), static_cast<float>(wb / sum), static_cast<float>(wc / sum)};
    return true;
}

// The deviation a pixel carries, as an atlas sample (value, depth, missing, valid).
AtlasSample pixel_sample(const DeviationMap& dev, std::size_t px, float missing_value) {
    AtlasSample s;
    if (dev.silhouette[px] == static_cast<std::uint8_t>(Silhouette::ReferenceOnly)) {
        s.value = missing_value;
        s.signed_depth = kNaN;
        s.missing = true;
    } else if (!std::isnan(dev.value[px])) {
        s.value = dev.value[px];
        s.signed_depth = dev.signed_depth[px];
    } else {
        s.valid = false;
    }
    return s;
}

bool reference_covered(const Frame& f, std::size_t px, float min_coverage) {
    return f.primitive_id[px] != kNoPrimitive && f.coverage[px] >= min_coverage;
}

std::size_t scatter(const Mesh& reference, const View& view, const Frame& frame, const DeviationMap& dev,
                    const BackprojectOptions& o, AtlasAccumulator& atlas, std::vector<std::int32_t>& scattered_in) {
    std::size_t covered = 0;
    for (int y = 0; y < frame.height; ++y) {
        for (int x = 0; x < frame.width; ++x) {
            const std::size_t px = static_cast<std::size_t>(y) * static_cast<std::size_t>(frame.width) +
                                   static_cast<std::size_t>(x);
            if (!reference_covered(frame, px, o.min_coverage)) continue;
            ++covered;
            AtlasSample s = pixel_sample(dev, px, o.missing_value);
            s.triangle = frame.primitive_id[px];
            double cos_inc = 0.0;
            if (!barycentric(reference, s.triangle, view.camera.pixel_ray(x + 0.5, y + 0.5), s.barycentric, cos_inc))
                continue;
            if (cos_inc < o.min_cos_incidence) continue;
            s.cos_incidence = static_cast<float>(cos_inc);
            atlas.add(s, view.index);
            for (const auto v : reference.triangles[s.triangle]) scattered_in[v] = view.index;
        }
    }
    return covered;
}

void gather(const Mesh& reference, const View& view, const Frame& frame, const DeviationMap& dev,
            const BackprojectOptions& o, AtlasAccumulator& atlas, const std::vector<std::int32_t>& scattered_in) {
    const double depth_tolerance = std::max(3.0 * view.footprint, 0.02 * o.framed_radius);
    const Vec3d eye = view.camera.eye();
    const Vec3d forward = view.camera.forward();
    const bool ortho = view.camera.projection == Projection::Orthographic;
    const Projector project(view.camera);
    for (std::size_t v = 0; v < reference.vertex_count(); ++v) {
        if (scattered_in[v] == view.index) continue;
        const Vec3d p = reference.positions[v].cast<double>();
        const Eigen::Vector3d uvd = project(p);
        if (!(uvd.x() >= 0 && uvd.y() >= 0 && uvd.x() < frame.width && uvd.y() < frame.height)) continue;
        const std::size_t px = static_cast<std::size_t>(uvd.y()) * static_cast<std::size_t>(frame.width) +
                               static_cast<std::size_t>(uvd.x());
        if (!reference_covered(frame, px, o.min_coverage)) continue;
        if (std::abs(frame.depth[px] - uvd.z()) > depth_tolerance) continue;
        const Vec3d to_camera = ortho ? Vec3d(-forward) : Vec3d((eye - p).normalized());
        const double cos_inc = reference.normals[v].cast<double>().dot(to_camera);
        if (cos_inc < o.min_cos_incidence) continue;
        AtlasSample s = pixel_sample(dev, px, o.missing_value);
        if (!s.valid) continue;
        s.cos_incidence = static_cast<float>(cos_inc);
        atlas.add_vertex(static_cast<std::uint32_t>(v), s, view.index);
    }
}

}  // namespace

std::size_t backproject_view(const Mesh& reference, const View& view, const Frame& reference_frame,
                             const DeviationMap& deviation, const BackprojectOptions& options,
                             AtlasAccumulator& atlas, BackprojectScratch& scratch) {
    GLINT_ASSERT(reference.has_normals(), "back-projection needs the reference's vertex normals");
    GLINT_ASSERT(deviation.value.size() == reference_frame.pixel_count(), "deviation map without metric values");
    if (scratch.scattered_in.size() != reference.vertex_count()) scratch.scattered_in.assign(reference.vertex_count(), -1);
    const std::size_t covered =
        scatter(reference, view, reference_frame, deviation, options, atlas, scratch.scattered_in);
    gather(reference, view, reference_frame, deviation, options, atlas, scratch.scattered_in);
    return covered;
}

}  // namespace glint
