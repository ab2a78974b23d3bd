#include "analysis/region_views.h"

#include "registration/closest_point.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {

namespace {

// A region's vertices as the directions see them: a subset spread evenly over the region, each
// carrying the dual area of the vertices it stands for.
struct RegionSamples {
    std::vector<Vec3d> point, normal;
    std::vector<double> area;
    double total_area = 0.0;
    Vec3d mean_normal = Vec3d::Zero();
};

std::vector<RegionSamples> region_samples(const Mesh& mesh, const std::vector<double>& areas,
                                          const std::vector<std::int32_t>& region_of_vertex,
                                          std::size_t regions) {
    std::vector<std::vector<std::uint32_t>> members(regions);
    for (std::size_t v = 0; v < region_of_vertex.size(); ++v) {
        const std::int32_t id = region_of_vertex[v];
        if (id >= 1 && static_cast<std::size_t>(id) <= regions)
            members[static_cast<std::size_t>(id - 1)].push_back(static_cast<std::uint32_t>(v));
    }
    std::vector<RegionSamples> out(regions);
    for (std::size_t r = 0; r < regions; ++r) {
        RegionSamples& s = out[r];
        const auto& m = members[r];
        for (const auto v : m) {
            s.total_area += areas[v];
            s.mean_normal += areas[v] * mesh.normals[v].cast<double>();
        }
        if (m.empty()) continue;
        // Every k-th vertex (vertices are stored near their neighbours), each standing for the
        // area of the k it skips.
        const std::size_t step = (m.size() + kViewSamples - 1) / kViewSamples;
        for (std::size_t i = 0; i < m.size(); i += step) {
            double a = 0.0;
            for (std::size_t j = i; j < std::min(m.size(), i + step); ++j) a += areas[m[j]];
            s.point.push_back(mesh.positions[m[i]].cast<double>());
            s.normal.push_back(mesh.normals[m[i]].cast<double>().normalized());
            s.area.push_back(a);
        }
        if (s.mean_normal.norm() > 0) s.mean_normal.normalize();
    }
    return out;
}

// The ray from a surface point towards the viewer leaves the surface: nothing hit before
// `distance` (the point is lifted off its own triangle by `lift` along its normal first).
bool unoccluded(const ClosestPointIndex& index, const Vec3d& p, const Vec3d& n, const Vec3d& to,
                double distance, double lift) {
    const RayHit hit = index.intersect({p + lift * n, to});
    return !hit.hit || hit.t >= distance;
}

// Visible projected area of a region from a direction all round (orthographic).
double visible_area(const ClosestPointIndex& index, const RegionSamples& s, const Vec3d& to,
                    double lift) {
    double sum = 0.0;
    for (std::size_t i = 0; i < s.point.size(); ++i) {
        const double c = s.normal[i].dot(to);
        if (c <= 0.0) continue;
        if (unoccluded(index, s.point[i], s.normal[i], to, std::numeric_limits<double>::infinity(),
                       lift))
            sum += s.area[i] * c;
    }
    return sum;
}

// Visible projected area of a region in a sweep view: in its frame, facing its camera, the ray
// to the camera unhit.
double visible_area(const ClosestPointIndex& index, const RegionSamples& s, const Camera& camera,
                    double lift) {
    const Projector project(camera);
    const bool ortho = camera.projection == Projection::Orthographic;
    double sum = 0.0;
    for (std::size_t i = 0; i < s.point.size(); ++i) {
        const Eigen::Vector3d uvz = project(s.point[i]);
        if (!(uvz.x() >= 0 && uvz.x() <= camera.width && uvz.y() >= 0 && uvz.y() <= camera.height &&
              uvz.z() > 0))
            continue;
        const Vec3d to = ortho ? Vec3d(-camera.forward()) : Vec3d(camera.eye() - s.point[i]);
        const double distance = ortho ? std::numeric_limits<double>::infinity() : to.norm();
        const Vec3d dir = to.normalized();
        const double c = s.normal[i].dot(dir);
        if (c <= 0.0) continue;
        if (unoccluded(index, s.point[i], s.normal[i], dir, distance, lift)) sum += s.area[i] * c;
    }
    return sum;
}

// kViewDirections directions spread evenly over the sphere (spherical Fibonacci).
std::vector<Vec3d> directions_all_round() {
    std::vector<Vec3d> out;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kViewDirections; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / kViewDirections;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        out.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return out;
}

}  // namespace

void choose_region_views(const Mesh& reference, const std::shared_ptr<const SurfaceIndex>& index,
                         const SweepPlan& plan, int zoom,
                         const std::vector<std::int32_t>& region_of_vertex,
                         std::vector<Region>& regions) {
    if (regions.empty() || !reference.has_normals() || reference.triangles.empty()) return;
    const ClosestPointIndex surface =
        index ? ClosestPointIndex(reference, index) : ClosestPointIndex::borrowing(reference);
    const std::vector<RegionSamples> samples =
        region_samples(reference, vertex_areas(reference), region_of_vertex, regions.size());
    // note: a lift of 1e-5 of the size keeps a ray off its own triangle (Embree's watertight
    // mode hits it at t ≈ 0 otherwise) and below any feature a picture could show.
    const double lift = 1e-5 * bounds(reference).diagonal();
    const std::vector<Vec3d> all_round = directions_all_round();
    tbb::parallel_for(std::size_t{0}, regions.size(), [&](std::size_t r) {
        const RegionSamples& s = samples[r];
        Region& region = regions[r];
        if (s.point.empty() || !(s.total_area > 0)) return;
        // All round: the mean normal first, so that it wins ties (the region seen square on).
        std::vector<Vec3d> tried;
        if (s.mean_normal.norm() > 0) tried.push_back(s.mean_normal);
        tried.insert(tried.end(), all_round.begin(), all_round.end());
        double best = -1.0;
        for (const Vec3d& d : tried) {
            const double a = visible_area(surface, s, d, lift);
            if (a > best * (1.0 + 1e-9)) {
                best = a;
                region.view_direction = d;
            }
        }
        region.visible_fraction = std::max(0.0, best) / s.total_area;
        double best_view = 0.0;
        for (const PlannedView& pv : plan.views) {
            if (pv.view.zoom_index != zoom) continue;
            const double a = visible_area(surface, s, pv.view.camera, lift);
            if (a > best_view * (1.0 + 1e-9)) {
                best_view = a;
                region.best_view = pv.view.index;
            }
        }
    });
}

}  // namespace glint
