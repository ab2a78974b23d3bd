// ICP machinery shared by the fine fit (icp.cpp) and the coarse hypotheses (coarse.cpp):
// surface sampling, matching with rejection, robust statistics, one ICP run. Internal.
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "registration/closest_point.h"
#include "registration/icp.h"

#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace glint::detail {

inline constexpr double kDeg = std::numbers::pi / 180.0;

/// A point on a surface with its interpolated unit normal.
struct Sample {
    Vec3d point;
    Vec3d normal;
};

/// `count` area-uniform samples with interpolated normals (deterministic for a seed).
[[nodiscard]] std::vector<Sample> sample_surface(const Mesh& mesh, int count, std::uint32_t seed);

/// `mesh` itself when it has vertex normals, else a copy in `storage` with angle-weighted ones
/// (as ClosestPointIndex computes them).
[[nodiscard]] const Mesh& with_vertex_normals(const Mesh& mesh, std::optional<Mesh>& storage);

/// Median of |v|, 0 for an empty vector.
[[nodiscard]] double median_abs(std::vector<double> v);

/// One examined sample matched with its closest reference point.
struct Pair {
    Vec3d p;   ///< examined sample, current pose (world)
    Vec3d q;   ///< closest reference point
    Vec3d n;   ///< reference normal at q
    double r;  ///< point-to-plane residual
};

/// Pairs of the examined samples at pose `t` with the reference, after rejection (distance,
/// normal compatibility, ROI).
[[nodiscard]] std::vector<Pair> match(const std::vector<Sample>& samples, const Rigid& t,
                                      const ClosestPointIndex& reference,
                                      const RegistrationOptions& o, double max_distance);

/// An ICP run: the pose reached and its result (evidence, log, termination).
struct IcpRun {
    Rigid t = Rigid::Identity();
    /// With options.fit_scale: the samples stand for center + scale × (p − center) before `t`
    /// moves them (`center`: the samples' centroid, where a scale is least coupled with the
    /// translation).
    double scale = 1.0;
    Vec3d center = Vec3d::Zero();
    RegistrationResult result;
};

/// `samples` as the similarity of `run` places them before its rigid motion: center + scale ×
/// (p − center); normals unchanged.
[[nodiscard]] std::vector<Sample> scaled(const std::vector<Sample>& samples, const IcpRun& run);

/// The relative scale one similarity step would add at `run`'s pose, and its jackknife standard
/// error over the eight octants about the samples' centre (see RegistrationResult::scale_trend).
struct ScaleTrend {
    double scale = 0.0;
    double uncertainty = 0.0;
};
[[nodiscard]] ScaleTrend scale_trend(const std::vector<Sample>& samples,
                                     const ClosestPointIndex& reference, const IcpRun& run,
                                     const RegistrationOptions& o, double diagonal);

/// Point-to-plane ICP from `start` for at most `max_iterations`; `ref_samples` and
/// `examined` are used only for the symmetric variant. `diagonal` is the larger bounding
/// diagonal (scales the tolerances). `solver_threads`: Ceres' threads per step (0 = the
/// machine's; 1 when several runs go in parallel).
[[nodiscard]] IcpRun run_icp(const std::vector<Sample>& samples,
                             const std::vector<Sample>& ref_samples,
                             const ClosestPointIndex& reference, const ClosestPointIndex* examined,
                             const Rigid& start, const RegistrationOptions& o, int max_iterations,
                             double diagonal, int solver_threads = 0);

}  // namespace glint::detail
