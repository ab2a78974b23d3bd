#include "scanner/backproject.h"

#include "mesh/error.h"
#include "mesh/geometry.h"
#include "mesh/mesh.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

namespace glint {

namespace {

// Barycentric weights of the point where `ray` meets the plane of triangle t, clamped to the
// triangle (the pixel centre may fall just outside the triangle its sub-sample hit).
// cos_incidence is signed: positive when the triangle's front (its winding's normal, the side
// its vertex normals point to) faces the camera.
bool barycentric(const Mesh& mesh, std::uint32_t t, const Ray& ray, std::array<float, 3>& w,
                 double& cos_incidence) {
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

// One worker's vertex range [first, last): the scatter samples that reach its vertices (all
// bands, pixel order), then the gather of those no sample reached.
void fold_range(const Mesh& reference, const View& view,
                std::span<const std::vector<AtlasSample>* const> bands, const ViewMaps& maps,
                const BackprojectOptions& o, AtlasAccumulator& atlas,
                std::vector<std::int32_t>& scattered_in, std::uint32_t first, std::uint32_t last) {
    for (const auto* band : bands)
        for (const AtlasSample& s : *band) {
            atlas.add(s, view.index, first, last);
            for (const auto v : reference.triangles[s.triangle])
                if (v >= first && v < last) scattered_in[v] = view.index;
        }
    const int width = maps.deviation.width, height = maps.deviation.height;
    const double depth_tolerance = std::max(3.0 * view.footprint, 0.02 * o.framed_radius);
    const Vec3d eye = view.camera.eye();
    const Vec3d forward = view.camera.forward();
    const bool ortho = view.camera.projection == Projection::Orthographic;
    const Projector project(view.camera);
    for (std::uint32_t v = first; v < last; ++v) {
        if (scattered_in[v] == view.index) continue;
        const Vec3d p = reference.positions[v].cast<double>();
        // note: the incidence test first (a dot product), the projection only for vertices
        // facing the camera; the tests are independent, so the order changes nothing else.
        const Vec3d to_camera = ortho ? Vec3d(-forward) : Vec3d((eye - p).normalized());
        const double cos_inc = reference.normals[v].cast<double>().dot(to_camera);
        if (cos_inc < o.min_cos_incidence) continue;
        const Eigen::Vector3d uvd = project(p);
        if (!(uvd.x() >= 0 && uvd.y() >= 0 && uvd.x() < width && uvd.y() < height)) continue;
        const std::size_t px = static_cast<std::size_t>(uvd.y()) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(uvd.x());
        if (!maps.reference_covered[px]) continue;
        if (std::abs(maps.reference_depth[px] - uvd.z()) > depth_tolerance) continue;
        AtlasSample s = pixel_sample(maps.deviation, px, o.missing_value);
        if (!s.valid) continue;
        s.cos_incidence = static_cast<float>(cos_inc);
        atlas.add_vertex(v, s, view.index);
    }
}

}  // namespace

void ViewMaps::resize(int width, int height) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    deviation.width = width;
    deviation.height = height;
    deviation.angle_deg.resize(n);
    deviation.signed_depth.resize(n);
    deviation.value.resize(n);
    deviation.silhouette.resize(n);
    reference_depth.resize(n);
    reference_covered.resize(n);
}

void record_reference_rows(const FrameRows& ref, float min_coverage, ViewMaps& maps) {
    const std::size_t first =
        static_cast<std::size_t>(ref.y0) * static_cast<std::size_t>(ref.width);
    for (std::size_t i = 0; i < ref.pixel_count(); ++i) {
        maps.reference_depth[first + i] = ref.depth[i];
        maps.reference_covered[first + i] =
            ref.primitive_id[i] != kNoPrimitive && ref.coverage[i] >= min_coverage;
    }
}

std::size_t scatter_rows(const Mesh& reference, const View& view, const FrameRows& ref,
                         const ViewMaps& maps, const BackprojectOptions& o,
                         std::vector<AtlasSample>& samples) {
    std::size_t covered = 0;
    for (int r = 0; r < ref.height; ++r) {
        const int y = ref.y0 + r;
        for (int x = 0; x < ref.width; ++x) {
            const std::size_t i =
                static_cast<std::size_t>(r) * static_cast<std::size_t>(ref.width) +
                static_cast<std::size_t>(x);
            if (ref.primitive_id[i] == kNoPrimitive || ref.coverage[i] < o.min_coverage) continue;
            ++covered;
            const std::size_t px =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(ref.width) +
                static_cast<std::size_t>(x);
            AtlasSample s = pixel_sample(maps.deviation, px, o.missing_value);
            s.triangle = ref.primitive_id[i];
            double cos_inc = 0.0;
            if (!barycentric(reference, s.triangle, view.camera.pixel_ray(x + 0.5, y + 0.5),
                             s.barycentric, cos_inc))
                continue;
            if (cos_inc < o.min_cos_incidence) continue;
            s.cos_incidence = static_cast<float>(cos_inc);
            GLINT_ASSERT(s.triangle < reference.triangle_count(),
                         "primitive id beyond the reference mesh");
            samples.push_back(s);
        }
    }
    return covered;
}

void fold_view(const Mesh& reference, const View& view,
               std::span<const std::vector<AtlasSample>* const> bands, const ViewMaps& maps,
               const BackprojectOptions& options, AtlasAccumulator& atlas,
               BackprojectScratch& scratch, int threads) {
    GLINT_ASSERT(reference.has_normals(), "back-projection needs the reference's vertex normals");
    const auto n = static_cast<std::uint32_t>(reference.vertex_count());
    if (scratch.scattered_in.size() != n) scratch.scattered_in.assign(n, -1);
    // note: one range per worker: each goes through every sample, so more ranges than
    // workers would only repeat that walk.
    const auto ranges = static_cast<std::uint32_t>(std::clamp(
        threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency()), 1, 64));
    tbb::task_arena arena(static_cast<int>(ranges));
    arena.execute([&] {
        tbb::parallel_for(std::uint32_t{0}, ranges, [&](std::uint32_t r) {
            const auto first = static_cast<std::uint32_t>(std::uint64_t{n} * r / ranges);
            const auto last = static_cast<std::uint32_t>(std::uint64_t{n} * (r + 1) / ranges);
            fold_range(reference, view, bands, maps, options, atlas, scratch.scattered_in, first,
                       last);
        });
    });
}

}  // namespace glint
