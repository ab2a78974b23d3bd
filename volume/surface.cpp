// Iso-surface extraction with VTK (flying edges, ROI cells, connectivity, windowed sinc) and
// meshoptimizer (decimation). See surface.h for the pipeline.
#include "volume/surface.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/validate.h"
#include "volume/contrast.h"
#include "volume/detail/vtk_steps.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace glint {

namespace {

std::string quoted_volume_of(const Volume& v) {
    return quoted_volume(v.path.empty() ? std::string("(generated)") : v.path.string());
}

std::string num(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", x);
    return b;
}

// Voxel bounds [lo, hi] (inclusive) holding the ROI, one voxel of margin so that the contour
// reaches the ROI's boundary; the whole volume without a ROI.
std::array<std::array<std::size_t, 3>, 2> crop_bounds(const VolumeGeometry& g,
                                                      const std::optional<Roi>& roi) {
    std::array<std::array<std::size_t, 3>, 2> out{};
    for (int d = 0; d < 3; ++d)
        out[1][static_cast<std::size_t>(d)] = g.size[static_cast<std::size_t>(d)] - 1;
    if (!roi) return out;
    const Vec3d lo =
        roi->shape == Roi::Shape::Sphere ? Vec3d(roi->center.array() - roi->radius) : roi->min;
    const Vec3d hi =
        roi->shape == Roi::Shape::Sphere ? Vec3d(roi->center.array() + roi->radius) : roi->max;
    Vec3d ilo = Vec3d::Constant(1e300), ihi = Vec3d::Constant(-1e300);
    for (int c = 0; c < 8; ++c) {
        const Vec3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                           (c & 4) ? hi.z() : lo.z());
        const Vec3d i = g.index_from_physical(corner);
        ilo = ilo.cwiseMin(i);
        ihi = ihi.cwiseMax(i);
    }
    for (std::size_t d = 0; d < 3; ++d) {
        const double n = static_cast<double>(g.size[d] - 1);
        const double a = std::floor(ilo[static_cast<Eigen::Index>(d)]) - 1,
                     b = std::ceil(ihi[static_cast<Eigen::Index>(d)]) + 1;
        if (b < 0 || a > n) return {{{1, 1, 1}, {0, 0, 0}}};  // empty: lo > hi
        out[0][d] = static_cast<std::size_t>(std::max(0.0, a));
        out[1][d] = static_cast<std::size_t>(std::min(n, b));
    }
    return out;
}

// Quadric decimation to the edge length, never moving the surface by more than the tolerance
// (meshoptimizer's error bound, relative to the mesh's scale); borders (ROI cuts) stay put.
void decimate(Mesh& mesh, const SurfaceOptions& o, double tolerance_mm, SurfaceReport& report) {
    const double area = surface_area(mesh);
    // An equilateral triangle of edge L has area √3/4 · L².
    const double per_triangle = std::sqrt(3.0) / 4.0 * o.edge_mm * o.edge_mm;
    const auto target = static_cast<std::size_t>(std::max(1.0, std::round(area / per_triangle)));
    if (target >= mesh.triangle_count()) {
        report.notes.push_back("decimation: already at or below the target edge length");
        return;
    }
    const std::size_t nv = mesh.vertex_count();
    const auto* xyz = reinterpret_cast<const float*>(mesh.positions.data());
    const float scale = meshopt_simplifyScale(xyz, nv, sizeof(Vec3f));
    std::vector<unsigned> indices(3 * mesh.triangle_count()), out(indices.size());
    std::copy_n(&mesh.triangles[0][0], indices.size(), indices.data());
    float error = 0.0f;
    const std::size_t kept = meshopt_simplify(
        out.data(), indices.data(), indices.size(), xyz, nv, sizeof(Vec3f), 3 * target,
        static_cast<float>(tolerance_mm / scale), meshopt_SimplifyLockBorder, &error);
    report.decimation_error_mm = static_cast<double>(error * scale);
    mesh.triangles.resize(kept / 3);
    std::copy_n(out.data(), kept, &mesh.triangles[0][0]);
    // Drop the vertices no triangle uses any more.
    std::vector<std::uint32_t> remap(nv, UINT32_MAX);
    std::vector<Vec3f> positions;
    for (auto& t : mesh.triangles)
        for (auto& v : t) {
            if (remap[v] == UINT32_MAX) {
                remap[v] = static_cast<std::uint32_t>(positions.size());
                positions.push_back(mesh.positions[v]);
            }
            v = remap[v];
        }
    mesh.positions = std::move(positions);
    report.notes.push_back("decimation to " + num(o.edge_mm) + " mm edges within " +
                           num(tolerance_mm) + " mm (estimated error " +
                           num(report.decimation_error_mm) + " mm)");
}

// The fewest triangles flying edges can make on the cropped voxels, counted before it runs
// (issue 23 item 9: a 107 KB compressed checkerboard made 66 M triangles in 47 s and 6.6 GB,
// whatever the budget). Flying edges puts one vertex on every voxel edge whose ends lie on
// either side of the iso value; a closed component has F = 2V - 4 triangles, at least 4V/3
// (the smallest, around one voxel, has 6 vertices and 8 triangles), so 4/3 × crossing edges
// stays under the count for every closed surface (a smooth one makes about 2V: the check after
// the contour catches what lies between).
std::uint64_t estimate_contour_triangles(const Volume& volume,
                                         const std::array<std::array<std::size_t, 3>, 2>& crop,
                                         double iso) {
    const VolumeGeometry& g = volume.geometry;
    const float* v = volume.voxels.data();
    const std::size_t sx = 1, sy = g.size[0], sz = g.size[0] * g.size[1];
    std::uint64_t crossings = 0;
    for (std::size_t k = crop[0][2]; k <= crop[1][2]; ++k) {
        throw_if_cancelled();
        for (std::size_t j = crop[0][1]; j <= crop[1][1]; ++j) {
            const std::size_t row = g.offset(0, j, k);
            for (std::size_t i = crop[0][0]; i <= crop[1][0]; ++i) {
                const std::size_t at = row + i;
                const bool above = v[at] > iso;
                if (i < crop[1][0]) crossings += (v[at + sx] > iso) != above;
                if (j < crop[1][1]) crossings += (v[at + sy] > iso) != above;
                if (k < crop[1][2]) crossings += (v[at + sz] > iso) != above;
            }
        }
    }
    return crossings * 4 / 3;
}

// The triangle budget (SurfaceOptions::max_triangles), before and after the contour.
void check_budget(const Volume& volume, double iso, std::uint64_t triangles, std::uint64_t budget,
                  bool estimated) {
    if (triangles <= budget) return;
    throw InputError(quoted_volume_of(volume) + ": the surface at iso " + num(iso) +
                     (estimated ? " would have at least about " : " has ") +
                     std::to_string(triangles) + " triangles" +
                     (estimated ? " (counted from the voxel edges it crosses)" : "") +
                     ", more than the budget of " + std::to_string(budget) +
                     " (--max-triangles); expected a surface within it: raise the budget, crop "
                     "with a surface ROI, or give another iso value");
}

// Where the scan saw: the grid (its outer voxels' centres bound the surface marching cubes can
// place) and the surface ROI that cropped it.
FieldOfView field_of_view(const VolumeGeometry& g, const std::optional<Roi>& roi) {
    FieldOfView f;
    Vec3d last;
    for (std::size_t d = 0; d < 3; ++d) last[static_cast<Eigen::Index>(d)] = double(g.size[d] - 1);
    f.boxes.push_back(
        {g.physical_from_index(Vec3d::Zero()), g.direction * g.spacing.asDiagonal(), last});
    if (roi && roi->shape == Roi::Shape::Box)
        f.boxes.push_back({roi->min, Eigen::Matrix3d::Identity(), roi->max - roi->min});
    if (roi && roi->shape == Roi::Shape::Sphere) f.balls.push_back({roi->center, roi->radius});
    return f;
}

}  // namespace

void SurfaceOptions::validate() const {
    if (!iso) throw OptionError("iso", "(none)", "an iso value is required");
    if (!std::isfinite(*iso)) throw OptionError("iso", *iso, "must be finite");
    if (roi && roi->shape == Roi::Shape::VertexMask)
        throw OptionError("surface_roi", to_string(*roi),
                          "a volume takes a sphere: or box: ROI, not a mask");
    if (roi && roi->shape == Roi::Shape::Sphere && !(roi->radius > 0))
        throw OptionError("surface_roi", to_string(*roi), "radius must be > 0");
    if (roi && roi->shape == Roi::Shape::Box && (roi->min.array() >= roi->max.array()).any())
        throw OptionError("surface_roi", to_string(*roi),
                          "box min must be below max on every axis");
    if (largest && seed) throw OptionError("largest", "true", "give largest or seed, not both");
    if (seed && !seed->allFinite())
        throw OptionError("seed", "(non-finite)", "must be a finite point");
    if (smooth_iterations < 0 || smooth_iterations > 1000)
        throw OptionError("smooth", smooth_iterations, "must be 0…1000 iterations");
    if (!(passband > 0 && passband < 2))
        throw OptionError("passband", passband, "must be in (0, 2)");
    if (!(edge_mm >= 0) || !std::isfinite(edge_mm))
        throw OptionError("edge", edge_mm, "must be ≥ 0 mm");
    if (!(tolerance_mm >= 0) || !std::isfinite(tolerance_mm))
        throw OptionError("tolerance", tolerance_mm, "must be ≥ 0 mm");
}

bool SurfaceOptions::any() const {
    return roi || largest || seed || smooth_iterations != 0 || edge_mm != 0 || tolerance_mm != 0;
}

ExtractedSurface extract_surface(const Volume& volume, const SurfaceOptions& o) {
    o.validate();
    const auto t0 = std::chrono::steady_clock::now();
    const VolumeGeometry& g = volume.geometry;
    ExtractedSurface out;
    SurfaceReport& r = out.report;
    r.voxels = g.size;
    r.spacing = g.spacing;
    r.iso = *o.iso;
    r.range = volume.range();
    if (!(r.iso > r.range[0] && r.iso < r.range[1]))
        throw InputError(quoted_volume_of(volume) + ": iso " + num(r.iso) +
                         " is outside the data range " + num(r.range[0]) + " … " + num(r.range[1]) +
                         "; give an iso value between them");
    const auto crop = crop_bounds(g, o.roi);
    for (std::size_t d = 0; d < 3; ++d) {
        if (crop[0][d] >= crop[1][d])
            throw InputError(quoted_volume_of(volume) + ": the surface ROI " + to_string(*o.roi) +
                             " holds no voxel of the volume");
        r.cropped[d] = crop[1][d] - crop[0][d] + 1;
    }
    const std::uint64_t budget = o.max_triangles > 0 ? o.max_triangles : default_max_triangles();
    check_budget(volume, r.iso, estimate_contour_triangles(volume, crop, r.iso), budget, true);
    detail::VtkSurface s = detail::contour(volume, crop, r.iso);
    check_budget(volume, r.iso, s.triangle_count(), budget, false);
    const std::string where = o.roi ? " inside the ROI " + to_string(*o.roi) : "";
    if (s.triangle_count() == 0)
        throw InputError(quoted_volume_of(volume) + ": the surface at iso " + num(r.iso) +
                         " is empty" + where);
    s.to_physical(g);
    if (o.roi) {
        s.keep_inside(*o.roi);
        if (s.triangle_count() == 0)
            throw InputError(quoted_volume_of(volume) + ": no triangle of the surface lies" +
                             where);
    }
    r.contour_triangles = s.triangle_count();
    if (o.largest || o.seed) {
        r.components_found = s.keep_component(o.seed);
        r.notes.push_back(o.seed ? "kept the component nearest the seed"
                                 : "kept the largest component");
    }
    if (o.smooth_iterations > 0) {
        s.smooth(o.smooth_iterations, o.passband);
        r.notes.push_back("windowed-sinc smoothing, " + std::to_string(o.smooth_iterations) +
                          " iterations, pass band " + num(o.passband));
    }
    out.mesh = s.to_mesh(g.direction.determinant() < 0);
    if (o.edge_mm > 0) {
        const double tolerance = o.tolerance_mm > 0 ? o.tolerance_mm : 0.25 * g.spacing.minCoeff();
        decimate(out.mesh, o, tolerance, r);
    }
    if (out.mesh.triangles.empty())
        throw InputError(quoted_volume_of(volume) + ": the surface at iso " + num(r.iso) +
                         " is empty" + where);
    out.mesh.unit = "mm";
    out.mesh.voxel_axes = g.direction * g.spacing.asDiagonal();
    out.mesh.field_of_view = field_of_view(g, o.roi);
    compute_vertex_normals(out.mesh);
    r.noise_sigma = noise_sigma(volume);
    out.mesh.faint = faint_vertices(volume, out.mesh, r.iso, kContrastSigmas * r.noise_sigma);
    const auto faint = std::count(out.mesh.faint.begin(), out.mesh.faint.end(), 1);
    r.notes.push_back("noise σ ≈ " + num(r.noise_sigma) + "; " +
                      num(100.0 * double(faint) / double(out.mesh.vertex_count())) +
                      " % of the vertices faint (within " + num(kContrastSigmas) +
                      " σ of the iso value for a voxel beside them: not compared)");
    std::vector<std::uint32_t> component;
    r.components_kept = connected_components(out.mesh, component);
    if (!o.largest && !o.seed) r.components_found = r.components_kept;
    r.triangles = out.mesh.triangle_count();
    r.vertices = out.mesh.vertex_count();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

std::string describe(const SurfaceReport& r) {
    char line[320];
    std::snprintf(
        line, sizeof line,
        "%zu x %zu x %zu voxels of %.4g x %.4g x %.4g mm, iso %.6g (data %.6g … %.6g): %zu triangles, %zu of "
        "%zu component(s), %.2f s",
        r.voxels[0], r.voxels[1], r.voxels[2], r.spacing.x(), r.spacing.y(), r.spacing.z(), r.iso,
        static_cast<double>(r.range[0]), static_cast<double>(r.range[1]), r.triangles,
        r.components_kept, r.components_found, r.seconds);
    return line;
}

}  // namespace glint
