#include "registration/detail/rotation_search.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace glint::detail {

Overlap overlap_at(const std::vector<Sample>& samples, const Rigid& t,
                   const ClosestPointIndex& reference, const RegistrationOptions& o,
                   double diagonal) {
    if (samples.empty()) return {};
    const auto pairs = match(samples, t, reference, o, o.overlap_distance * diagonal);
    std::vector<double> r(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) r[i] = pairs[i].r;
    return {static_cast<double>(pairs.size()) / static_cast<double>(samples.size()),
            median_abs(std::move(r))};
}

namespace {

// note: 64 of the 366 poses go on to ICP — with all of them bun270's search cost 6 s of CPU
// (18–29 s wall on the shared 2-core machine).
constexpr std::size_t kRefinedPoses = 64;

// Centroid, RMS radius about it, and the unit mean normal (zero when the normals cancel).
struct Spread {
    Vec3d centroid = Vec3d::Zero();
    double radius = 0.0;
    Vec3d mean_normal = Vec3d::Zero();
};

Spread spread_of(const std::vector<Sample>& s) {
    Spread out;
    if (s.empty()) return out;
    for (const auto& x : s) {
        out.centroid += x.point;
        out.mean_normal += x.normal;
    }
    out.centroid /= static_cast<double>(s.size());
    for (const auto& x : s) out.radius += (x.point - out.centroid).squaredNorm();
    out.radius = std::sqrt(out.radius / static_cast<double>(s.size()));
    // A closed surface's normals cancel: no side to push it to.
    if (out.mean_normal.norm() > 0.2 * static_cast<double>(s.size())) out.mean_normal.normalize();
    else out.mean_normal = Vec3d::Zero();
    return out;
}

// Rotations spread over all orientations: the identity, then 26 axes on a Fibonacci sphere
// (the upper half suffices with the angles' signs) by ±45°, ±90°, ±135° and 180°.
std::vector<Eigen::Matrix3d> rotations() {
    std::vector<Eigen::Matrix3d> out{Eigen::Matrix3d::Identity()};
    constexpr int kAxes = 26;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kAxes; ++i) {
        const double z = 1.0 - (static_cast<double>(i) + 0.5) / kAxes;  // upper hemisphere
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const Vec3d axis(r * std::cos(golden * i), r * std::sin(golden * i), z);
        for (double deg : {45.0, 90.0, 135.0, 180.0, -45.0, -90.0, -135.0}) {
            out.push_back(
                Eigen::AngleAxisd(deg * std::numbers::pi / 180.0, axis.normalized()).matrix());
        }
    }
    return out;
}

}  // namespace

std::vector<Rigid> search_poses(const std::vector<Sample>& reference,
                                const std::vector<Sample>& examined) {
    const Spread ref = spread_of(reference), exa = spread_of(examined);
    std::vector<Rigid> out;
    for (const auto& rot : rotations()) {
        // The examined centroid at the reference's, or pushed out along its (rotated) mean
        // normal by half the reference's radius: where a scan of one side lies.
        const double pushes[2] = {0.0, 0.5};
        for (double push : pushes) {
            if (push > 0 && exa.mean_normal.isZero()) continue;
            Rigid t = Rigid::Identity();
            t.linear() = rot;
            t.translation() =
                ref.centroid + push * ref.radius * (rot * exa.mean_normal) - rot * exa.centroid;
            out.push_back(t);
        }
    }
    return out;
}

std::vector<CoarseHypothesis> rotation_search(const ClosestPointIndex& reference,
                                              const std::vector<Sample>& reference_samples,
                                              const std::vector<Sample>& quick_samples,
                                              const RegistrationOptions& quick, double diagonal,
                                              std::size_t keep) {
    const std::vector<Rigid> all = search_poses(reference_samples, quick_samples);
    const std::vector<Sample> few(
        quick_samples.begin(),
        quick_samples.begin() +
            static_cast<std::ptrdiff_t>(std::min<std::size_t>(200, quick_samples.size())));
    // Pass 0: every pose as it is, scored by the share of a few samples within 3 % of the size
    // of a compatible reference surface (no ICP: a few milliseconds for all of them).
    RegistrationOptions generous = quick;
    generous.overlap_distance = 0.03;
    std::vector<double> raw(all.size());
    tbb::parallel_for(std::size_t{0}, all.size(), [&](std::size_t k) {
        raw[k] = overlap_at(few, all[k], reference, generous, diagonal).share;
    });
    std::vector<std::size_t> rank(all.size());
    for (std::size_t k = 0; k < rank.size(); ++k) rank[k] = k;
    std::stable_sort(rank.begin(), rank.end(),
                     [&](std::size_t a, std::size_t b) { return raw[a] > raw[b]; });
    rank.resize(std::min<std::size_t>(rank.size(), kRefinedPoses));
    std::vector<Rigid> poses;
    for (const auto k : rank) poses.push_back(all[k]);
    // Pass 1: those, a few samples, a few short iterations. note: 200 samples, 6 iterations of 3
    // solver steps — the pass only has to bring the right pose ahead of the wrong ones.
    RegistrationOptions rough = quick;
    rough.inner_iterations = 3;
    std::vector<CoarseHypothesis> tried(poses.size());
    tbb::parallel_for(std::size_t{0}, poses.size(), [&](std::size_t k) {
        const IcpRun r = run_icp(few, {}, reference, nullptr, poses[k], rough, 6, diagonal, 1);
        const Overlap ov = overlap_at(few, r.t, reference, quick, diagonal);
        tried[k] = {r.t, "", -ov.share + 1e-3 * ov.median_residual / diagonal};
    });
    std::vector<std::size_t> order(tried.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return tried[a].score < tried[b].score; });
    order.resize(std::min(order.size(), 2 * keep));
    // Second pass: the best of them with the quick settings.
    std::vector<CoarseHypothesis> best(order.size());
    tbb::parallel_for(std::size_t{0}, order.size(), [&](std::size_t i) {
        const IcpRun r = run_icp(quick_samples, {}, reference, nullptr,
                                 tried[order[i]].reference_from_examined, quick, 12, diagonal, 1);
        const Overlap ov = overlap_at(quick_samples, r.t, reference, quick, diagonal);
        std::ostringstream name;
        name << "rotation search (" << all.size() << " poses), overlap " << ov.share;
        best[i] = {r.t, name.str(), -ov.share + 1e-3 * ov.median_residual / diagonal};
    });
    std::sort(best.begin(), best.end(),
              [](const auto& a, const auto& b) { return a.score < b.score; });
    if (best.size() > keep) best.resize(keep);
    return best;
}

}  // namespace glint::detail
