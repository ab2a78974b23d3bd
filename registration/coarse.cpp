#include "registration/coarse.h"

#include "mesh/error.h"
#include "registration/detail/coarse.h"
#include "registration/detail/icp_core.h"
#include "registration/detail/rotation_search.h"

#include <tbb/parallel_for.h>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <limits>
#include <optional>
#include <sstream>

namespace glint {

namespace detail {

namespace {

// Principal frame (columns = axes by decreasing variance, right-handed) and centroid.
void principal_frame(const std::vector<Sample>& s, Vec3d& centroid, Eigen::Matrix3d& axes) {
    centroid = Vec3d::Zero();
    for (const auto& x : s) centroid += x.point;
    centroid /= static_cast<double>(s.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& x : s) cov += (x.point - centroid) * (x.point - centroid).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    axes.col(0) = eig.eigenvectors().col(2);
    axes.col(1) = eig.eigenvectors().col(1);
    axes.col(2) = axes.col(0).cross(axes.col(1));
}

// Identity, and the principal frames matched under every proper sign flip.
std::vector<CoarseHypothesis> hypotheses(const std::vector<Sample>& reference,
                                         const std::vector<Sample>& examined) {
    Vec3d cr, ce;
    Eigen::Matrix3d ar, ae;
    principal_frame(reference, cr, ar);
    principal_frame(examined, ce, ae);
    std::vector<CoarseHypothesis> out{{Rigid::Identity(), "identity", 0.0}};
    const double flips[4][3] = {{1, 1, 1}, {-1, -1, 1}, {-1, 1, -1}, {1, -1, -1}};
    for (const auto& f : flips) {
        Rigid h = Rigid::Identity();
        h.linear() = ar * Vec3d(f[0], f[1], f[2]).asDiagonal() * ae.transpose();
        h.translation() = cr - h.linear() * ce;
        std::ostringstream name;
        name << "principal axes, signs (" << f[0] << ", " << f[1] << ", " << f[2] << ")";
        out.push_back({h, name.str(), 0.0});
    }
    return out;
}

// When the kept hypothesis lays too little of the examined surface onto the reference (a
// partial scan whose principal axes are not the whole's), the rotation search
// (registration/detail/rotation_search.h) runs; its best fit replaces the kept one when it lays
// clearly more of the surface on the reference.
void search_if_partial(const ClosestPointIndex& reference, const std::vector<Sample>& quick_samples,
                       const RegistrationOptions& quick, double diagonal, std::uint32_t seed,
                       CoarseAlignment& out) {
    const Overlap kept =
        overlap_at(quick_samples, out.reference_from_examined, reference, quick, diagonal);
    if (kept.share >= kSearchBelowOverlap) return;
    auto found = rotation_search(reference, sample_surface(reference.mesh(), 4000, seed + 2),
                                 quick_samples, quick, diagonal);
    for (const auto& h : found) out.hypotheses.push_back(h);
    if (found.empty()) return;
    const Overlap best = overlap_at(quick_samples, found.front().reference_from_examined, reference,
                                    quick, diagonal);
    std::ostringstream why;
    if (best.share > kept.share + 0.05) {
        why << found.front().name << " (the principal axes laid " << kept.share
            << " of the examined surface on the reference: a partial scan?)";
        out.reference_from_examined = found.front().reference_from_examined;
        out.description = why.str();
    } else {
        why << " (a rotation search found no better pose: best overlap " << best.share << ")";
        out.description += why.str();
    }
}

}  // namespace

CoarseAlignment coarse_align(const ClosestPointIndex& reference, const Mesh& examined,
                             const std::vector<Sample>& samples, const RegistrationOptions& o,
                             double diagonal) {
    RegistrationOptions quick = o;
    quick.samples = std::min(o.samples, 2000);
    quick.symmetric = false;
    quick.fit_scale = false;  // the hypotheses are ranked by a rigid fit; the fine fit scales
    const auto quick_samples = sample_surface(examined, quick.samples, o.seed + 3);
    CoarseAlignment out;
    // The hypotheses' short runs are independent: one task each (Ceres single-threaded in
    // each), kept in the hypotheses' order.
    std::vector<CoarseHypothesis> tried =
        hypotheses(sample_surface(reference.mesh(), 4000, o.seed + 2), samples);
    std::vector<std::uint8_t> ran(tried.size(), 0);
    tbb::parallel_for(std::size_t{0}, tried.size(), [&](std::size_t k) {
        CoarseHypothesis& h = tried[k];
        const IcpRun r = run_icp(quick_samples, {}, reference, nullptr, h.reference_from_examined,
                                 quick, 12, diagonal, 1);
        if (r.result.log.empty()) return;
        // Score: robust residual spread, penalised by how much of the surface matched.
        const auto pairs =
            match(quick_samples, r.t, reference, quick, std::numeric_limits<double>::infinity());
        std::vector<double> res(pairs.size());
        for (std::size_t i = 0; i < pairs.size(); ++i) res[i] = pairs[i].r;
        const double frac =
            static_cast<double>(pairs.size()) / static_cast<double>(quick_samples.size());
        h.score =
            (median_abs(res) + 1e-12 * diagonal) / std::max(frac, 1e-3) / std::max(frac, 1e-3);
        h.reference_from_examined = r.t;
        ran[k] = 1;
    });
    for (std::size_t k = 0; k < tried.size(); ++k)
        if (ran[k]) out.hypotheses.push_back(tried[k]);
    out.description = "identity";
    if (out.hypotheses.empty()) return out;
    double best = std::numeric_limits<double>::max();
    for (const auto& c : out.hypotheses) best = std::min(best, c.score);
    // A shape with a symmetry (a sphere, an ellipsoid, a symmetric part) fits equally well in
    // several poses: the robust loss discounts the very damage that tells them apart. Among
    // hypotheses that score within 1.5× of the best, keep the one that turns the examined
    // mesh least, i.e. trust the scan's own placement.
    // note: 1.5× — measured: the four flips of a 12 × 8 × 6 ellipsoid with a bump scored
    // within 0.2 % of each other; the condyle phantom's wrong flips score 260× worse than its
    // right ones.
    const CoarseHypothesis* pick = nullptr;
    std::size_t tied = 0;
    auto angle = [](const Rigid& t) { return Eigen::AngleAxisd(t.linear()).angle(); };
    for (const auto& c : out.hypotheses) {
        if (c.score > 1.5 * best) continue;
        ++tied;
        if (pick == nullptr ||
            angle(c.reference_from_examined) < angle(pick->reference_from_examined))
            pick = &c;
    }
    out.reference_from_examined = pick->reference_from_examined;
    out.description = pick->name;
    if (tied > 1)
        out.description +=
            " (" + std::to_string(tied) +
            " hypotheses fit about equally, the shape may be symmetric: kept the smallest rotation)";
    search_if_partial(reference, quick_samples, quick, diagonal, o.seed, out);
    return out;
}

}  // namespace detail

CoarseAlignment coarse_align(const Mesh& reference, const Mesh& examined,
                             const RegistrationOptions& options) {
    options.validate();
    if (reference.triangles.empty() || examined.triangles.empty())
        throw InputError("coarse alignment: both meshes need triangles");
    const ClosestPointIndex ref_index(reference);
    std::optional<Mesh> with_normals;
    const Mesh& exam = detail::with_vertex_normals(examined, with_normals);
    const double diagonal = std::max(bounds(reference).diagonal(), bounds(exam).diagonal());
    const auto samples = detail::sample_surface(exam, options.samples, options.seed);
    return detail::coarse_align(ref_index, exam, samples, options, diagonal);
}

}  // namespace glint
