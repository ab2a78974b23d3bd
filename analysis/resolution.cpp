#include "analysis/resolution.h"

#include "mesh/geometry.h"
#include "registration/closest_point.h"
#include "volume/contrast.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace glint {

double voxel_extent_along(const Eigen::Matrix3d& axes, const Vec3d& n) {
    return std::abs(n.dot(axes.col(0))) + std::abs(n.dot(axes.col(1))) +
           std::abs(n.dot(axes.col(2)));
}

double staircase_step(const Eigen::Matrix3d& axes, const Vec3d& n) {
    return std::max(
        {std::abs(n.dot(axes.col(0))), std::abs(n.dot(axes.col(1))), std::abs(n.dot(axes.col(2)))});
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The width of one voxel of the coarser grid seen along unit direction d.
double voxel_width(const ResolutionGrids& grids, const Vec3d& d) {
    double w = 0.0;
    if (grids.reference) w = voxel_extent_along(*grids.reference, d);
    if (grids.examined) w = std::max(w, voxel_extent_along(*grids.examined, d));
    return w;
}

// The step of the coarser grid's staircase along unit direction d (staircase_step).
double grid_step(const ResolutionGrids& grids, const Vec3d& d) {
    double s = 0.0;
    if (grids.reference) s = staircase_step(*grids.reference, d);
    if (grids.examined) s = std::max(s, staircase_step(*grids.examined, d));
    return s;
}

// Distance along the unit direction d from o to the first surface beyond `skip` (inf: none).
double first_hit(const ClosestPointIndex& index, const Vec3d& o, const Vec3d& d, double skip) {
    const RayHit h = index.intersect({o + skip * d, d});
    return h.hit ? skip + h.t : kInf;
}

// The reference's own clearance at p: the gap outside or the thickness inside, the nearer.
double reference_clearance(const ClosestPointIndex& index, const Vec3d& p, const Vec3d& n,
                           double skip) {
    return std::min(first_hit(index, p, n, skip), first_hit(index, p, -n, skip));
}

// The examined surface on the line through p along n: its clearance, from the examined sheet
// nearest p to the next examined sheet on either side of it, and how far that sheet lies from p.
struct ExaminedLine {
    double clearance = kInf;
    double offset = kInf;
};
ExaminedLine examined_clearance(const ClosestPointIndex& index, const Vec3d& p, const Vec3d& n,
                                double skip) {
    const double out = first_hit(index, p, n, 0.0);
    const double in = first_hit(index, p, -n, 0.0);
    if (!std::isfinite(out) && !std::isfinite(in)) return {};
    const Vec3d d = out <= in ? n : Vec3d(-n);
    const Vec3d sheet = p + std::min(out, in) * d;
    return {std::min(first_hit(index, sheet, d, skip), first_hit(index, sheet, -d, skip)),
            std::min(out, in)};
}

// The solid's thinnest across a cone of kConeRays rays tilted kConeTiltDeg from `inward` at
// o, each hit's distance in voxels of the coarser grid seen along its ray (+inf: none hit).
double cone_voxels(const ClosestPointIndex& index, const Vec3d& o, const Vec3d& inward, double skip,
                   const ResolutionGrids& grids) {
    const Vec3d u = inward.unitOrthogonal();
    const Vec3d w = inward.cross(u);
    const double tilt = kConeTiltDeg * std::numbers::pi / 180.0;
    double best = kInf;
    for (int k = 0; k < kConeRays; ++k) {
        const double phi = 2.0 * std::numbers::pi * k / kConeRays;
        const Vec3d d =
            std::cos(tilt) * inward + std::sin(tilt) * (std::cos(phi) * u + std::sin(phi) * w);
        const double t = first_hit(index, o, d, skip);
        if (std::isfinite(t)) best = std::min(best, t / voxel_width(grids, d));
    }
    return best;
}

// Whether either scan's surface is faint at reference vertex v (Mesh::faint): its own flag, or
// a corner of the closest examined triangle that the closest point depends on.
bool faint_here(const Mesh& reference, const Mesh& fitted, const ClosestPointIndex& exa,
                std::size_t v, const Vec3d& p, bool examined_too) {
    if (reference.faint.size() == reference.vertex_count() && reference.faint[v]) return true;
    if (!examined_too || fitted.faint.size() != fitted.vertex_count()) return false;
    const ClosestPoint c = exa.closest(p);
    const auto& t = fitted.triangles[c.triangle];
    for (std::size_t k = 0; k < 3; ++k)
        if (c.barycentric[static_cast<Eigen::Index>(k)] > 1e-9 && fitted.faint[t[k]]) return true;
    return false;
}

std::string rule_text(const ResolutionGrids& grids) {
    const auto grid = [&](const std::optional<Eigen::Matrix3d>& a, bool detected, bool smoothed) {
        if (!a) return std::string("no grid (a mesh file)");
        std::ostringstream s;
        s.precision(3);
        s << a->col(0).norm() << " × " << a->col(1).norm() << " × " << a->col(2).norm();
        if (detected)
            s << (smoothed ? ", the marching-cubes grid its smoothed vertices still crowd near"
                           : ", the marching-cubes grid its vertices lie on");
        return s.str();
    };
    std::ostringstream s;
    s << "below resolution: another sheet of either surface closer, along the vertex's normal, "
         "than "
      << kResolutionVoxels << " voxel(s) of the coarser grid seen along that normal, or the "
      << "reference's own far side closer along one of " << kConeRays << " rays tilted "
      << kConeTiltDeg << "° inward (reference "
      << grid(grids.reference, grids.reference_detected, grids.reference_smoothed) << ", examined "
      << grid(grids.examined, grids.examined_detected, grids.examined_smoothed)
      << (grids.given ? "; --resolution for a mesh file" : "")
      << "): a thin plate, a thin process's tip or a narrow gap, where partial volume decides "
         "each scan's surface; or either scan's surface faint there (its volume within "
      << kContrastSigmas
      << " noise σ of the iso value for a voxel beside it: noise and partial volume place it)";
    return s.str();
}

}  // namespace

ResolutionGrids resolution_grids(const Mesh& reference, const Mesh& examined,
                                 std::optional<double> given) {
    ResolutionGrids g{reference.voxel_axes, examined.voxel_axes, false};
    const auto fill = [&](std::optional<Eigen::Matrix3d>& a) {
        if (a || !given) return;
        a = Eigen::Matrix3d::Identity() * *given;
        g.given = true;
    };
    fill(g.reference);
    fill(g.examined);
    return g;
}

ResolutionEvidence below_resolution(const Mesh& reference, const Mesh& fitted,
                                    const ResolutionGrids& grids,
                                    std::shared_ptr<const SurfaceIndex> reference_index,
                                    std::shared_ptr<const SurfaceIndex> examined_index) {
    ResolutionEvidence out;
    if (!grids.reference && !grids.examined) return out;
    if (reference.vertex_count() == 0 || fitted.triangle_count() == 0) return out;
    out.rule = rule_text(grids);
    if (!reference_index) reference_index = index_surface(reference);
    if (!examined_index) examined_index = index_surface(fitted);
    const ClosestPointIndex ref(reference, reference_index);
    const ClosestPointIndex exa(fitted, examined_index);
    const std::size_t n = reference.vertex_count();
    // note: rays start a thousandth of the voxel off the surface, so that the vertex's own
    // triangles are not hit at t ≈ 0.
    const Eigen::Matrix3d& axes = grids.reference ? *grids.reference : *grids.examined;
    const double skip = 1e-3 * axes.colwise().norm().minCoeff();
    out.below.assign(n, 0);
    std::vector<std::uint8_t> faint(n, 0);
    out.clearance.assign(n, std::numeric_limits<float>::infinity());
    out.sampling.assign(n, 0.0f);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t v = r.begin(); v != r.end(); ++v) {
                              const Vec3d p = reference.positions[v].cast<double>();
                              const Vec3d nv = reference.normals[v].cast<double>();
                              if (!(nv.squaredNorm() > 0.5)) continue;
                              const double voxel = voxel_width(grids, nv);
                              out.sampling[v] = static_cast<float>(grid_step(grids, nv));
                              const double own = reference_clearance(ref, p, nv, skip);
                              const ExaminedLine e = examined_clearance(exa, p, nv, skip);
                              out.clearance[v] = static_cast<float>(std::min(own, e.clearance));
                              const double k = kResolutionVoxels;
                              const bool resolved =  // the reference, along n and across
                                  own >= k * voxel && cone_voxels(ref, p, -nv, skip, grids) >= k;
                              const bool examined_thin = e.clearance < k * voxel;
                              // Where the reference resolves and the examined surface lies
                              // farther than a voxel from it, material was lost or gained (an
                              // erosion that thinned the bone below a voxel, its faint floor):
                              // a change larger than partial volume can make, whatever the
                              // examined scan's own thinness or contrast there.
                              const bool lost = resolved && e.offset > k * voxel;
                              out.below[v] = (!resolved || examined_thin) && !lost ? 1 : 0;
                              if (faint_here(reference, fitted, exa, v, p, !lost)) faint[v] = 1;
                          }
                      });
    const auto area = vertex_areas(reference);
    for (std::size_t v = 0; v < n; ++v) {
        if (faint[v]) out.faint_area += area[v];
        out.below[v] = out.below[v] || faint[v];
        if (out.below[v]) out.flagged_area += area[v];
    }
    return out;
}

}  // namespace glint
