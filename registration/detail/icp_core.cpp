#include "registration/detail/icp_core.h"

#include "mesh/normals.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

namespace glint::detail {

// Area-uniform samples: a triangle picked with probability ∝ area, a uniform point in it.
const Mesh& with_vertex_normals(const Mesh& mesh, std::optional<Mesh>& storage) {
    if (mesh.has_normals()) return mesh;
    storage = mesh;
    compute_vertex_normals(*storage);
    return *storage;
}

std::vector<Sample> sample_surface(const Mesh& mesh, int count, std::uint32_t seed) {
    const auto areas = triangle_areas(mesh);
    std::vector<double> cumulative(areas.size());
    double total = 0.0;
    for (std::size_t t = 0; t < areas.size(); ++t) cumulative[t] = total += areas[t];
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::vector<Sample> out;
    out.reserve(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
        const double pick = u01(rng) * total;
        const auto t = static_cast<std::size_t>(
            std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
        const auto& tri = mesh.triangles[std::min(t, areas.size() - 1)];
        // Uniform point in a triangle: (1 − √r1, √r1(1 − r2), √r1 r2).
        const double r1 = std::sqrt(u01(rng)), r2 = u01(rng);
        const double w[3] = {1 - r1, r1 * (1 - r2), r1 * r2};
        Sample s{Vec3d::Zero(), Vec3d::Zero()};
        for (int k = 0; k < 3; ++k) {
            s.point += w[k] * mesh.positions[tri[static_cast<std::size_t>(k)]].cast<double>();
            s.normal += w[k] * mesh.normals[tri[static_cast<std::size_t>(k)]].cast<double>();
        }
        if (s.normal.norm() > 0) s.normal.normalize();
        out.push_back(s);
    }
    return out;
}

double median_abs(std::vector<double> v) {
    if (v.empty()) return 0.0;
    for (auto& x : v) x = std::abs(x);
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

namespace {

// r = n_q · (R(x) p + t − q): point-to-plane residual of one pair, x = (angle-axis, t).
struct PointToPlane {
    Vec3d p, q, n;
    template <class T>
    bool operator()(const T* x, T* r) const {
        const T pt[3] = {T(p.x()), T(p.y()), T(p.z())};
        T rp[3];
        ceres::AngleAxisRotatePoint(x, pt, rp);
        r[0] = T(n.x()) * (rp[0] + x[3] - T(q.x())) + T(n.y()) * (rp[1] + x[4] - T(q.y())) +
               T(n.z()) * (rp[2] + x[5] - T(q.z()));
        return true;
    }
};

// Symmetric direction: a reference point q against the plane of an examined point p with
// normal n, both moving with the examined mesh: r = (R n) · (q − (R p + t)).
struct PlaneToPoint {
    Vec3d p, q, n;
    template <class T>
    bool operator()(const T* x, T* r) const {
        const T pt[3] = {T(p.x()), T(p.y()), T(p.z())};
        const T nt[3] = {T(n.x()), T(n.y()), T(n.z())};
        T rp[3], rn[3];
        ceres::AngleAxisRotatePoint(x, pt, rp);
        ceres::AngleAxisRotatePoint(x, nt, rn);
        r[0] = rn[0] * (T(q.x()) - rp[0] - x[3]) + rn[1] * (T(q.y()) - rp[1] - x[4]) +
               rn[2] * (T(q.z()) - rp[2] - x[5]);
        return true;
    }
};

// A similarity step about the centre c: r = n · (R(e^s (p − c)) + c + t − q), x = (angle-axis,
// t, s). The scale enters as its logarithm (positive for any step), about the samples' centroid
// (where a scale moves the surface least and is least confused with a translation).
struct PointToPlaneScaled {
    Vec3d p, q, n, c;
    template <class T>
    bool operator()(const T* x, T* r) const {
        using std::exp;
        const T k = exp(x[6]);
        const T pt[3] = {k * T(p.x() - c.x()), k * T(p.y() - c.y()), k * T(p.z() - c.z())};
        T rp[3];
        ceres::AngleAxisRotatePoint(x, pt, rp);
        r[0] = T(n.x()) * (rp[0] + T(c.x()) + x[3] - T(q.x())) +
               T(n.y()) * (rp[1] + T(c.y()) + x[4] - T(q.y())) +
               T(n.z()) * (rp[2] + T(c.z()) + x[5] - T(q.z()));
        return true;
    }
};

// The symmetric direction of a similarity step: a reference point q against the plane of an
// examined point p (world, current pose) with normal n, both moving with the step about c:
// r = (R n) · (q − (R(e^s (p − c)) + c + t)).
struct PlaneToPointScaled {
    Vec3d p, q, n, c;
    template <class T>
    bool operator()(const T* x, T* r) const {
        using std::exp;
        const T k = exp(x[6]);
        const T pt[3] = {k * T(p.x() - c.x()), k * T(p.y() - c.y()), k * T(p.z() - c.z())};
        const T nt[3] = {T(n.x()), T(n.y()), T(n.z())};
        T rp[3], rn[3];
        ceres::AngleAxisRotatePoint(x, pt, rp);
        ceres::AngleAxisRotatePoint(x, nt, rn);
        r[0] = rn[0] * (T(q.x()) - rp[0] - T(c.x()) - x[3]) +
               rn[1] * (T(q.y()) - rp[1] - T(c.y()) - x[4]) +
               rn[2] * (T(q.z()) - rp[2] - T(c.z()) - x[5]);
        return true;
    }
};

ceres::LossFunction* make_loss(RobustLoss loss, double scale) {
    switch (loss) {
        case RobustLoss::None: return nullptr;
        case RobustLoss::Huber: return new ceres::HuberLoss(scale);
        case RobustLoss::Cauchy: return new ceres::CauchyLoss(scale);
        case RobustLoss::Tukey: return new ceres::TukeyLoss(scale);
    }
    return nullptr;
}

Rigid from_params(const double* x) {
    Eigen::Matrix3d r;
    ceres::AngleAxisToRotationMatrix(x, ceres::ColumnMajorAdapter3x3(r.data()));
    Rigid t = Rigid::Identity();
    t.linear() = r;
    t.translation() = Vec3d(x[3], x[4], x[5]);
    return t;
}

// Whether a closest reference point lies in the ROI (a vertex mask keeps a triangle with at
// least one masked vertex).
bool in_roi(const ClosestPoint& c, const Mesh& ref, const std::optional<Roi>& roi) {
    if (!roi) return true;
    if (roi->shape == Roi::Shape::VertexMask) {
        const auto& tri = ref.triangles[c.triangle];
        return roi->vertex_mask[tri[0]] || roi->vertex_mask[tri[1]] || roi->vertex_mask[tri[2]];
    }
    return roi->contains_point(c.point);
}

}  // namespace

// Pairs of the examined samples at pose T with the reference, after rejection.
std::vector<Pair> match(const std::vector<Sample>& samples, const Rigid& t,
                        const ClosestPointIndex& reference, const RegistrationOptions& o,
                        double max_distance) {
    std::vector<Vec3d> moved(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) moved[i] = t * samples[i].point;
    const auto cps = reference.closest(moved, max_distance);
    const double min_cos = std::cos(o.max_normal_angle_deg * kDeg);
    const Eigen::Matrix3d rot = t.linear();
    std::vector<Pair> pairs;
    pairs.reserve(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const auto& c = cps[i];
        if (!c.found) continue;
        if ((rot * samples[i].normal).dot(c.normal) < min_cos) continue;
        if (!in_roi(c, reference.mesh(), o.roi)) continue;
        pairs.push_back({moved[i], c.point, c.normal, c.normal.dot(moved[i] - c.point)});
    }
    return pairs;
}

namespace {

/// Residuals within 3σ: how many, and their RMS (0 when none).
struct InlierStats {
    std::size_t inliers = 0;
    double rms = 0.0;
};

InlierStats inlier_stats(const std::vector<double>& residuals, double sigma) {
    InlierStats st;
    double ss = 0.0;
    for (double r : residuals)
        if (std::abs(r) <= 3.0 * sigma) {
            ++st.inliers;
            ss += r * r;
        }
    st.rms = st.inliers ? std::sqrt(ss / static_cast<double>(st.inliers)) : 0.0;
    return st;
}

struct IcpEvidence {
    double rms = 0.0;
    double inlier_fraction = 0.0;
    double overlap = 0.0;
};

// The evidence at pose T (see RegistrationResult): closest points without a distance limit,
// so that a sample whose closest point lies outside the ROI is left out rather than counted
// as not overlapping; a pair is accepted within `gate` with compatible normals.
// note: the gate is absolute (a share of the size), not a multiple of the residuals' spread:
// a fit of unrelated surfaces has a wide spread, and a relative gate would call it overlap.
IcpEvidence evaluate(const std::vector<Sample>& samples, const Rigid& t,
                     const ClosestPointIndex& reference, const RegistrationOptions& o,
                     double gate) {
    std::vector<Vec3d> moved(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) moved[i] = t * samples[i].point;
    const auto cps = reference.closest(moved);
    const double min_cos = std::cos(o.max_normal_angle_deg * kDeg);
    const Eigen::Matrix3d rot = t.linear();
    std::size_t candidates = 0;
    std::vector<double> residuals;
    residuals.reserve(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const auto& c = cps[i];
        if (!c.found) continue;
        if (!in_roi(c, reference.mesh(), o.roi)) continue;
        ++candidates;
        if (c.distance > gate || (rot * samples[i].normal).dot(c.normal) < min_cos) continue;
        residuals.push_back(c.normal.dot(moved[i] - c.point));
    }
    IcpEvidence e;
    if (candidates == 0 || residuals.empty()) return e;
    e.overlap = static_cast<double>(residuals.size()) / static_cast<double>(candidates);
    const InlierStats st = inlier_stats(residuals, 1.4826 * median_abs(residuals));
    e.inlier_fraction = static_cast<double>(st.inliers) / static_cast<double>(residuals.size());
    e.rms = st.rms;
    return e;
}

// One linearised step: the pairs' point-to-plane residuals (and, symmetric, the reference
// samples against the examined planes) under the robust loss of `scale`, solved for a small
// motion x = (angle-axis, translation) applied on top of `t`.
struct StepSolution {
    Rigid step = Rigid::Identity();
    double log_scale = 0.0;  ///< with a scale centre: ln of the step's scale about it
    ceres::Solver::Summary summary;
};

ceres::Solver::Options solver_options(const RegistrationOptions& o, int threads) {
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = o.inner_iterations;
    so.num_threads =
        threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    so.logging_type = ceres::SILENT;
    so.minimizer_progress_to_stdout = false;
    return so;
}

// The symmetric fit's second set of pairs at a similarity pose: the reference samples taken
// back into the examined mesh's frame (through the pose and the scale about `run.center`),
// their closest examined points and normals brought forward again (world).
struct BackPair {
    Vec3d p, q, n;
};

std::vector<BackPair> back_pairs(const std::vector<Sample>& ref_samples,
                                 const ClosestPointIndex& examined, const IcpRun& run,
                                 const RegistrationOptions& o, double max_distance) {
    const Rigid inv = run.t.inverse();
    std::vector<Vec3d> back(ref_samples.size());
    for (std::size_t i = 0; i < ref_samples.size(); ++i)
        back[i] = run.center + (inv * ref_samples[i].point - run.center) / run.scale;
    const auto cps = examined.closest(back, max_distance / run.scale);
    std::vector<BackPair> out;
    for (std::size_t i = 0; i < cps.size(); ++i) {
        if (!cps[i].found) continue;
        const Vec3d pw = run.t * (run.center + run.scale * (cps[i].point - run.center));
        const Vec3d nw = run.t.linear() * cps[i].normal;
        if (nw.dot(ref_samples[i].normal) < std::cos(o.max_normal_angle_deg * kDeg)) continue;
        out.push_back({pw, ref_samples[i].point, nw});
    }
    return out;
}

// A similarity step about `center` on the pairs (and, symmetric, the reference samples against
// the examined planes): the rigid part (rotation about the centre) and the logarithm of the
// scale.
StepSolution solve_scaled_step(const std::vector<Pair>& pairs, const Vec3d& center,
                               const RegistrationOptions& o, double scale, int threads,
                               const std::vector<BackPair>& back = {}) {
    double x[7] = {0, 0, 0, 0, 0, 0, 0};
    const std::unique_ptr<ceres::LossFunction> loss(make_loss(o.loss, scale));
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    for (const auto& p : pairs)
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PointToPlaneScaled, 1, 7>(
                                     new PointToPlaneScaled{p.p, p.q, p.n, center}),
                                 loss.get(), x);
    for (const auto& b : back)
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PlaneToPointScaled, 1, 7>(
                                     new PlaneToPointScaled{b.p, b.q, b.n, center}),
                                 loss.get(), x);
    StepSolution out;
    ceres::Solve(solver_options(o, threads), &problem, &out.summary);
    // p ↦ R(p − c) + c + t: rotation R, translation c − R c + t.
    out.step = from_params(x);
    out.step.translation() += center - out.step.linear() * center;
    out.log_scale = x[6];
    return out;
}

StepSolution solve_step(const std::vector<Pair>& pairs, const std::vector<Sample>& ref_samples,
                        const ClosestPointIndex* examined, const Rigid& t,
                        const RegistrationOptions& o, double scale, double max_distance,
                        int threads) {
    double x[6] = {0, 0, 0, 0, 0, 0};
    // note: one loss function for every residual (the problem does not own it): a loss per
    // residual was one allocation and one free per pair and iteration, for the same function.
    const std::unique_ptr<ceres::LossFunction> loss(make_loss(o.loss, scale));
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    for (const auto& p : pairs)
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<PointToPlane, 1, 6>(new PointToPlane{p.p, p.q, p.n}),
            loss.get(), x);
    if (o.symmetric && examined) {
        const Rigid inv = t.inverse();
        std::vector<Vec3d> back(ref_samples.size());
        for (std::size_t i = 0; i < ref_samples.size(); ++i) back[i] = inv * ref_samples[i].point;
        const auto cps = examined->closest(back, max_distance);
        for (std::size_t i = 0; i < cps.size(); ++i) {
            if (!cps[i].found) continue;
            const Vec3d pw = t * cps[i].point;
            const Vec3d nw = t.linear() * cps[i].normal;
            if (nw.dot(ref_samples[i].normal) < std::cos(o.max_normal_angle_deg * kDeg)) continue;
            problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PlaneToPoint, 1, 6>(
                                         new PlaneToPoint{pw, ref_samples[i].point, nw}),
                                     loss.get(), x);
        }
    }
    StepSolution out;
    ceres::Solve(solver_options(o, threads), &problem, &out.summary);
    out.step = from_params(x);
    return out;
}

// Whether the iteration just logged ends the run (converged or failed); fills the
// termination fields. `previous_cost` is the cost of the previous fully annealed iteration.
bool finished(const IcpIteration& log, bool annealed, const std::optional<double>& previous_cost,
              const RegistrationOptions& o, double diagonal, RegistrationResult& res) {
    if (annealed && log.rotation_step_deg < o.rotation_tolerance_deg &&
        log.translation_step < o.translation_tolerance * diagonal &&
        log.scale_step < o.translation_tolerance) {
        res.converged = true;
        res.termination = "parameter change";
        std::ostringstream why;
        why << "parameter change: step " << log.rotation_step_deg << "° / " << log.translation_step
            << " below " << o.rotation_tolerance_deg << "° and " << o.translation_tolerance
            << " × size after " << log.iteration << " iterations";
        res.termination_detail = why.str();
        return true;
    }
    if (annealed && previous_cost) {
        // note: the denominator's floor keeps 0/0 (a perfect fit) from reading as a change.
        const double change = std::abs(log.cost - *previous_cost) /
                              std::max(*previous_cost, std::numeric_limits<double>::min());
        if (change < o.cost_tolerance) {
            res.converged = true;
            res.termination = "cost change";
            std::ostringstream why;
            why << "cost change: relative change " << change << " below " << o.cost_tolerance
                << " after " << log.iteration << " iterations";
            res.termination_detail = why.str();
            return true;
        }
    }
    return false;
}

// The evidence at the pose returned (not at the one before the last step); too little
// overlap turns a converged run into "low overlap".
void judge_overlap(const std::vector<Sample>& samples, const ClosestPointIndex& reference,
                   const RegistrationOptions& o, double diagonal, IcpRun& run) {
    RegistrationResult& res = run.result;
    const IcpEvidence e = evaluate(samples, run.t, reference, o, o.overlap_distance * diagonal);
    res.rms = e.rms;
    res.inlier_fraction = e.inlier_fraction;
    res.overlap = e.overlap;
    if (e.overlap < o.min_overlap) {
        res.converged = false;
        res.termination = "low overlap";
        std::ostringstream why;
        why << "low overlap: " << e.overlap << " of the samples lie within " << o.overlap_distance
            << " × size of a compatible reference surface at the final pose, below min overlap "
            << o.min_overlap << " (ICP: " << res.termination_detail << ")";
        res.termination_detail = why.str();
    }
}

}  // namespace

IcpRun run_icp(const std::vector<Sample>& samples, const std::vector<Sample>& ref_samples,
               const ClosestPointIndex& reference, const ClosestPointIndex* examined,
               const Rigid& start, const RegistrationOptions& o, int max_iterations,
               double diagonal, int solver_threads) {
    IcpRun run;
    run.t = start;
    if (o.fit_scale && !samples.empty()) {
        for (const auto& s : samples) run.center += s.point;
        run.center /= static_cast<double>(samples.size());
    }
    RegistrationResult& res = run.result;
    res.termination = "max iterations";
    res.termination_detail =
        "max iterations: " + std::to_string(max_iterations) + " iterations without convergence";
    // note: 1e-9 of the size keeps the loss scale positive on noise-free synthetic pairs.
    const double sigma_floor = 1e-9 * diagonal;
    double max_distance = std::numeric_limits<double>::infinity();
    // Cost of the previous iteration when its loss scale was already fully annealed (the
    // costs of two iterations compare only under the same anneal factor).
    std::optional<double> previous_cost;
    for (int it = 0; it < max_iterations; ++it) {
        const std::vector<Pair> pairs =
            match(o.fit_scale ? scaled(samples, run) : samples, run.t, reference, o, max_distance);
        if (pairs.size() < std::max<std::size_t>(6, samples.size() / 33)) {
            res.termination = "no overlap";
            res.termination_detail = "no overlap: " + std::to_string(pairs.size()) + " of " +
                                     std::to_string(samples.size()) +
                                     " samples found a compatible reference surface";
            res.converged = false;
            res.iterations = it;
            return run;
        }
        std::vector<double> residuals(pairs.size());
        for (std::size_t i = 0; i < pairs.size(); ++i) residuals[i] = pairs[i].r;
        const double sigma = std::max(1.4826 * median_abs(residuals), sigma_floor);
        const double anneal = std::max(o.anneal_end, o.anneal_start / std::pow(2.0, it));
        const double scale = anneal * sigma;
        // Far outliers (beyond 20σ, or the initial spread) do not enter the next matching.
        max_distance = std::max(20.0 * sigma, 1e-6 * diagonal);
        const StepSolution solved =
            o.fit_scale
                ? solve_scaled_step(pairs, run.t * run.center, o, scale, solver_threads,
                                    o.symmetric && examined
                                        ? back_pairs(ref_samples, *examined, run, o, max_distance)
                                        : std::vector<BackPair>{})
                : solve_step(pairs, ref_samples, examined, run.t, o, scale, max_distance,
                             solver_threads);
        run.t = solved.step * run.t;
        run.scale *= std::exp(solved.log_scale);
        IcpIteration log;
        log.iteration = it + 1;
        log.cost = solved.summary.final_cost;
        log.rms = inlier_stats(residuals, sigma).rms;
        log.loss_scale = o.loss == RobustLoss::None ? 0.0 : scale;
        log.overlap = static_cast<double>(pairs.size()) / static_cast<double>(samples.size());
        log.rotation_step_deg = rotation_angle_deg(solved.step);
        log.translation_step = solved.step.translation().norm();
        log.scale_step = std::abs(solved.log_scale);
        res.log.push_back(log);
        res.iterations = it + 1;
        if (solved.summary.termination_type == ceres::FAILURE) {
            res.termination = "solver failure";
            res.termination_detail = "solver failure: " + solved.summary.message;
            break;
        }
        const bool annealed = anneal <= o.anneal_end || o.loss == RobustLoss::None;
        if (finished(log, annealed, previous_cost, o, diagonal, res)) break;
        if (annealed) previous_cost = log.cost;
    }
    judge_overlap(o.fit_scale ? scaled(samples, run) : samples, reference, o, diagonal, run);
    return run;
}

std::vector<Sample> scaled(const std::vector<Sample>& samples, const IcpRun& run) {
    std::vector<Sample> out = samples;
    if (run.scale == 1.0) return out;
    for (auto& s : out) s.point = run.center + run.scale * (s.point - run.center);
    return out;
}

ScaleTrend scale_trend(const std::vector<Sample>& samples, const ClosestPointIndex& reference,
                       const IcpRun& run, const RegistrationOptions& o, double diagonal) {
    ScaleTrend out;
    const std::vector<Sample> placed = scaled(samples, run);
    // The pairs at the final pose as the fine fit's last matching keeps them: within the
    // overlap gate, then within 20σ (a sample beyond the reference's border matches a point
    // of the border whose plane it may lie close to: it is far from it).
    std::vector<Pair> pairs = match(placed, run.t, reference, o, o.overlap_distance * diagonal);
    std::vector<double> residuals(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) residuals[i] = pairs[i].r;
    const double sigma = std::max(1.4826 * median_abs(residuals), 1e-9 * diagonal);
    const double keep = std::max(20.0 * sigma, 1e-6 * diagonal);
    std::erase_if(pairs, [&](const Pair& p) { return (p.p - p.q).norm() > keep; });
    if (pairs.size() < 64) return out;
    const double loss_scale = o.anneal_end * sigma;
    Vec3d center = Vec3d::Zero();
    for (const auto& p : pairs) center += p.p;
    center /= static_cast<double>(pairs.size());
    // One robustly weighted Gauss-Newton step of the similarity about the centre from the pose
    // reached (the weights of the loss at its final scale): residual n·(p − q), Jacobian row
    // [((p − c) × n)ᵀ, nᵀ, n·(p − c)] (rotation, translation, log-scale). Its normal equations
    // are sums over the pairs, so the estimate without one block is the total less that block's
    // share: the jackknife below costs nine 7×7 solves.
    using Matrix7 = Eigen::Matrix<double, 7, 7>;
    using Vector7 = Eigen::Matrix<double, 7, 1>;
    const auto weight = [&](double r) {
        const double u = (r * r) / (loss_scale * loss_scale);
        switch (o.loss) {
            case RobustLoss::None: return 1.0;
            case RobustLoss::Huber: return u <= 1.0 ? 1.0 : 1.0 / std::sqrt(u);
            case RobustLoss::Cauchy: return 1.0 / (1.0 + u);
            case RobustLoss::Tukey: return u <= 1.0 ? (1.0 - u) * (1.0 - u) : 0.0;
        }
        return 1.0;
    };
    // note: neighbouring residuals are correlated (noise in a scan is smooth, a damage is one
    // patch), so the least-squares standard error, which takes 20000 samples as independent,
    // is far too small. The jackknife over eight spatial blocks (the octants of the principal
    // frame about the centre) widens it as the correlation does: delete-one-block estimates
    // s_k, SE² = (K − 1)/K Σ (s_k − s̄)².
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : pairs) cov += (p.p - center) * (p.p - center).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> frame(cov);
    std::array<Matrix7, 8> normal;
    std::array<Vector7, 8> rhs;
    std::array<std::size_t, 8> count{};
    for (int b = 0; b < 8; ++b) {
        normal[static_cast<std::size_t>(b)].setZero();
        rhs[static_cast<std::size_t>(b)].setZero();
    }
    for (const auto& p : pairs) {
        const Vec3d a = p.p - center;
        const Vec3d d = frame.eigenvectors().transpose() * a;
        const auto b = static_cast<std::size_t>((d.x() > 0 ? 1 : 0) | (d.y() > 0 ? 2 : 0) |
                                                (d.z() > 0 ? 4 : 0));
        Vector7 j;
        j << a.cross(p.n), p.n, p.n.dot(a);
        const double w = weight(p.r);
        normal[b] += w * j * j.transpose();
        rhs[b] += w * j * p.r;
        ++count[b];
    }
    Matrix7 all_normal = Matrix7::Zero();
    Vector7 all_rhs = Vector7::Zero();
    for (std::size_t b = 0; b < 8; ++b) {
        all_normal += normal[b];
        all_rhs += rhs[b];
    }
    // The log-scale of the step (−J⁻¹ r), as a relative scale; nothing when the system is
    // singular (a plane or a line of pairs: no scale can be told).
    const auto scale_of = [](const Matrix7& m, const Vector7& v) -> std::optional<double> {
        // note: a column-pivoting QR with its rank (an LDLT of the fixed 7×7 tripped GCC 12's
        // maybe-uninitialized warning inside Eigen).
        Eigen::ColPivHouseholderQR<Matrix7> solved(m);
        solved.setThreshold(1e-12);
        if (solved.rank() < 7) return std::nullopt;
        const Vector7 x = -solved.solve(v);
        return std::isfinite(x[6]) ? std::optional<double>(std::expm1(x[6])) : std::nullopt;
    };
    const auto whole = scale_of(all_normal, all_rhs);
    if (!whole) return out;
    out.scale = *whole;
    std::vector<double> estimates;
    for (std::size_t b = 0; b < 8; ++b) {
        if (count[b] == 0 || pairs.size() - count[b] < 64) continue;
        if (const auto e = scale_of(all_normal - normal[b], all_rhs - rhs[b]))
            estimates.push_back(*e);
    }
    const auto k = static_cast<double>(estimates.size());
    if (estimates.size() < 2) return out;
    double mean = 0.0, ss = 0.0;
    for (double e : estimates) mean += e / k;
    for (double e : estimates) ss += (e - mean) * (e - mean);
    out.uncertainty = std::sqrt((k - 1.0) / k * ss);
    return out;
}

}  // namespace glint::detail
