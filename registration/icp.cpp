#include "registration/icp.h"

#include "mesh/error.h"
#include "mesh/parse.h"
#include "registration/closest_point.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

namespace glint {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Sample {
    Vec3d point;
    Vec3d normal;
};

// Area-uniform samples with interpolated normals (deterministic for a seed).
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
        const auto t = static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
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
        r[0] = rn[0] * (T(q.x()) - rp[0] - x[3]) + rn[1] * (T(q.y()) - rp[1] - x[4]) + rn[2] * (T(q.z()) - rp[2] - x[5]);
        return true;
    }
};

double median_abs(std::vector<double> v) {
    if (v.empty()) return 0.0;
    for (auto& x : v) x = std::abs(x);
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

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

struct Pair {
    Vec3d p;   // examined sample, current pose (world)
    Vec3d q;   // closest reference point
    Vec3d n;   // reference normal at q
    double r;  // point-to-plane residual
};

// Whether a closest reference point lies in the ROI (a vertex mask keeps a triangle with at
// least one masked vertex).
bool in_roi(const ClosestPoint& c, const Mesh& ref, const RegistrationRoi& roi) {
    if (roi.shape == RegistrationRoi::Shape::VertexMask) {
        const auto& tri = ref.triangles[c.triangle];
        return roi.vertex_mask[tri[0]] || roi.vertex_mask[tri[1]] || roi.vertex_mask[tri[2]];
    }
    return roi.shape == RegistrationRoi::Shape::None || roi.contains(c.point);
}

// Pairs of the examined samples at pose T with the reference, after rejection.
std::vector<Pair> match(const std::vector<Sample>& samples, const Rigid& t, const ClosestPointIndex& reference,
                        const RegistrationOptions& o, double max_distance) {
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

struct Evidence {
    double rms = 0.0;
    double inlier_fraction = 0.0;
    double overlap = 0.0;
};

// The evidence at pose T (see RegistrationResult): closest points without a distance limit,
// so that a sample whose closest point lies outside the ROI is left out rather than counted
// as not overlapping; a pair is accepted within `gate` with compatible normals.
// note: the gate is absolute (a share of the size), not a multiple of the residuals' spread:
// a fit of unrelated surfaces has a wide spread, and a relative gate would call it overlap.
Evidence evaluate(const std::vector<Sample>& samples, const Rigid& t, const ClosestPointIndex& reference,
                  const RegistrationOptions& o, double gate) {
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
    Evidence e;
    if (candidates == 0 || residuals.empty()) return e;
    e.overlap = static_cast<double>(residuals.size()) / static_cast<double>(candidates);
    const InlierStats st = inlier_stats(residuals, 1.4826 * median_abs(residuals));
    e.inlier_fraction = static_cast<double>(st.inliers) / static_cast<double>(residuals.size());
    e.rms = st.rms;
    return e;
}

struct IcpRun {
    Rigid t = Rigid::Identity();
    RegistrationResult result;
};

IcpRun run_icp(const std::vector<Sample>& samples, const std::vector<Sample>& ref_samples,
               const ClosestPointIndex& reference, const ClosestPointIndex* examined, const Rigid& start,
               const RegistrationOptions& o, int max_iterations, double diagonal) {
    IcpRun run;
    run.t = start;
    RegistrationResult& res = run.result;
    res.termination = "max iterations";
    res.termination_detail = "max iterations: " + std::to_string(max_iterations) + " iterations without convergence";
    // note: 1e-9 of the size keeps the loss scale positive on noise-free synthetic pairs.
    const double sigma_floor = 1e-9 * diagonal;
    double max_distance = std::numeric_limits<double>::infinity();
    // Cost of the previous iteration when its loss scale was already fully annealed (the
    // costs of two iterations compare only under the same anneal factor).
    std::optional<double> previous_cost;
    for (int it = 0; it < max_iterations; ++it) {
        const std::vector<Pair> pairs = match(samples, run.t, reference, o, max_distance);
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

        double x[6] = {0, 0, 0, 0, 0, 0};
        ceres::Problem::Options problem_options;
        ceres::Problem problem(problem_options);
        for (const auto& p : pairs)
            problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PointToPlane, 1, 6>(new PointToPlane{p.p, p.q, p.n}),
                                     make_loss(o.loss, scale), x);
        if (o.symmetric && examined) {
            const Rigid inv = run.t.inverse();
            std::vector<Vec3d> back(ref_samples.size());
            for (std::size_t i = 0; i < ref_samples.size(); ++i) back[i] = inv * ref_samples[i].point;
            const auto cps = examined->closest(back, max_distance);
            for (std::size_t i = 0; i < cps.size(); ++i) {
                if (!cps[i].found) continue;
                const Vec3d pw = run.t * cps[i].point;
                const Vec3d nw = run.t.linear() * cps[i].normal;
                if (nw.dot(ref_samples[i].normal) < std::cos(o.max_normal_angle_deg * kDeg)) continue;
                problem.AddResidualBlock(
                    new ceres::AutoDiffCostFunction<PlaneToPoint, 1, 6>(new PlaneToPoint{pw, ref_samples[i].point, nw}),
                    make_loss(o.loss, scale), x);
            }
        }
        ceres::Solver::Options so;
        so.linear_solver_type = ceres::DENSE_QR;
        so.max_num_iterations = o.inner_iterations;
        so.num_threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        so.logging_type = ceres::SILENT;
        so.minimizer_progress_to_stdout = false;
        ceres::Solver::Summary summary;
        ceres::Solve(so, &problem, &summary);

        const Rigid step = from_params(x);
        run.t = step * run.t;
        IcpIteration log;
        log.iteration = it + 1;
        log.cost = summary.final_cost;
        log.rms = inlier_stats(residuals, sigma).rms;
        log.loss_scale = o.loss == RobustLoss::None ? 0.0 : scale;
        log.overlap = static_cast<double>(pairs.size()) / static_cast<double>(samples.size());
        log.rotation_step_deg = rotation_angle_deg(step);
        log.translation_step = step.translation().norm();
        res.log.push_back(log);
        res.iterations = it + 1;
        if (summary.termination_type == ceres::FAILURE) {
            res.termination = "solver failure";
            res.termination_detail = "solver failure: " + summary.message;
            break;
        }
        const bool annealed = anneal <= o.anneal_end || o.loss == RobustLoss::None;
        if (annealed && log.rotation_step_deg < o.rotation_tolerance_deg &&
            log.translation_step < o.translation_tolerance * diagonal) {
            res.converged = true;
            res.termination = "parameter change";
            std::ostringstream why;
            why << "parameter change: step " << log.rotation_step_deg << "° / " << log.translation_step
                << " below " << o.rotation_tolerance_deg << "° and " << o.translation_tolerance << " × size after "
                << it + 1 << " iterations";
            res.termination_detail = why.str();
            break;
        }
        if (annealed && previous_cost) {
            // note: the denominator's floor keeps 0/0 (a perfect fit) from reading as a change.
            const double change = std::abs(log.cost - *previous_cost) /
                                  std::max(*previous_cost, std::numeric_limits<double>::min());
            if (change < o.cost_tolerance) {
                res.converged = true;
                res.termination = "cost change";
                std::ostringstream why;
                why << "cost change: relative change " << change << " below " << o.cost_tolerance << " after "
                    << it + 1 << " iterations";
                res.termination_detail = why.str();
                break;
            }
        }
        if (annealed) previous_cost = log.cost;
    }
    // The evidence at the pose returned, not at the one before the last step.
    const Evidence e = evaluate(samples, run.t, reference, o, o.overlap_distance * diagonal);
    res.rms = e.rms;
    res.inlier_fraction = e.inlier_fraction;
    res.overlap = e.overlap;
    if (e.overlap < o.min_overlap) {
        res.converged = false;
        res.termination = "low overlap";
        std::ostringstream why;
        why << "low overlap: " << e.overlap << " of the samples lie within " << o.overlap_distance
            << " × size of a compatible reference surface at the final pose, below min overlap " << o.min_overlap
            << " (ICP: " << res.termination_detail << ")";
        res.termination_detail = why.str();
    }
    return run;
}

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

}  // namespace

RobustLoss parse_loss(const std::string& text) {
    if (text == "none") return RobustLoss::None;
    if (text == "huber") return RobustLoss::Huber;
    if (text == "cauchy") return RobustLoss::Cauchy;
    if (text == "tukey") return RobustLoss::Tukey;
    throw InputError("loss '" + text + "': expected none, huber, cauchy or tukey");
}

std::string to_string(RobustLoss loss) {
    switch (loss) {
        case RobustLoss::None: return "none";
        case RobustLoss::Huber: return "huber";
        case RobustLoss::Cauchy: return "cauchy";
        case RobustLoss::Tukey: return "tukey";
    }
    return "?";
}

bool RegistrationRoi::contains(const Vec3d& p) const {
    switch (shape) {
        case Shape::None: return true;
        case Shape::Sphere: return (p - center).norm() <= radius;
        case Shape::Box: return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
        case Shape::VertexMask: return true;
    }
    return true;
}

RegistrationRoi parse_registration_roi(const std::string& text) {
    RegistrationRoi roi;
    const auto colon = text.find(':');
    const std::string kind = text.substr(0, colon);
    const std::vector<double> v =
        parse_number_list(colon == std::string::npos ? "" : std::string_view(text).substr(colon + 1), "ROI '" + text + "'");
    if (kind == "sphere" && v.size() == 4 && v[3] > 0) {
        roi.shape = RegistrationRoi::Shape::Sphere;
        roi.center = {v[0], v[1], v[2]};
        roi.radius = v[3];
    } else if (kind == "box" && v.size() == 6) {
        roi.shape = RegistrationRoi::Shape::Box;
        roi.min = {v[0], v[1], v[2]};
        roi.max = {v[3], v[4], v[5]};
    } else {
        throw InputError("ROI '" + text + "': expected sphere:x,y,z,r (r > 0) or box:x0,y0,z0,x1,y1,z1");
    }
    return roi;
}

void RegistrationOptions::validate() const {
    auto bad = [](const std::string& field, double value, const std::string& rule) {
        std::ostringstream s;
        s << "registration: " << field << " = " << value << ": " << rule;
        throw InputError(s.str());
    };
    if (samples < 50) bad("samples", samples, "must be ≥ 50");
    if (max_iterations < 1) bad("max iterations", max_iterations, "must be ≥ 1");
    if (inner_iterations < 1) bad("inner iterations", inner_iterations, "must be ≥ 1");
    if (!(anneal_end > 0) || anneal_start < anneal_end) bad("anneal", anneal_start, "needs start ≥ end > 0");
    if (!(max_normal_angle_deg > 0 && max_normal_angle_deg <= 180)) bad("max normal angle", max_normal_angle_deg, "must be in (0, 180]");
    if (!(cost_tolerance >= 0)) bad("cost tolerance", cost_tolerance, "must be ≥ 0");
    if (!(min_overlap >= 0 && min_overlap <= 1)) bad("min overlap", min_overlap, "must be in [0, 1]");
    if (!(overlap_distance > 0)) bad("overlap distance", overlap_distance, "must be > 0");
}

RegistrationResult register_meshes(const Mesh& reference, const Mesh& examined, const RegistrationOptions& o) {
    o.validate();
    if (reference.triangles.empty() || examined.triangles.empty())
        throw InputError("registration: both meshes need triangles");
    if (o.roi.shape == RegistrationRoi::Shape::VertexMask && o.roi.vertex_mask.size() != reference.vertex_count())
        throw InputError("registration: the ROI vertex mask has " + std::to_string(o.roi.vertex_mask.size()) +
                         " entries, the reference has " + std::to_string(reference.vertex_count()) + " vertices");
    if (o.roi.shape != RegistrationRoi::Shape::None) {
        std::size_t inside = 0;
        for (std::size_t v = 0; v < reference.vertex_count(); ++v)
            inside += o.roi.shape == RegistrationRoi::Shape::VertexMask
                          ? o.roi.vertex_mask[v] != 0
                          : o.roi.contains(reference.positions[v].cast<double>());
        if (inside == 0) throw InputError("registration: the ROI contains no vertex of the reference mesh");
    }
    const ClosestPointIndex ref_index(reference);
    // The index computes angle-weighted normals when the mesh has none.
    const ClosestPointIndex exa_index(examined);
    const Mesh& exam = exa_index.mesh();
    const double diagonal = std::max(bounds(reference).diagonal(), bounds(exam).diagonal());
    const auto samples = sample_surface(exam, o.samples, o.seed);
    const auto ref_samples = o.symmetric ? sample_surface(ref_index.mesh(), o.samples / 2, o.seed + 1) : std::vector<Sample>{};

    Rigid start = o.initial.value_or(Rigid::Identity());
    std::string coarse = o.initial ? "given initial pose" : "identity";
    if (o.coarse && !o.initial) {
        // Hypotheses: identity, and the principal frames matched under every proper sign flip.
        Vec3d cr, ce;
        Eigen::Matrix3d ar, ae;
        principal_frame(sample_surface(ref_index.mesh(), 4000, o.seed + 2), cr, ar);
        principal_frame(samples, ce, ae);
        std::vector<std::pair<Rigid, std::string>> hypotheses{{Rigid::Identity(), "identity"}};
        const double flips[4][3] = {{1, 1, 1}, {-1, -1, 1}, {-1, 1, -1}, {1, -1, -1}};
        for (const auto& f : flips) {
            Rigid h = Rigid::Identity();
            h.linear() = ar * Vec3d(f[0], f[1], f[2]).asDiagonal() * ae.transpose();
            h.translation() = cr - h.linear() * ce;
            std::ostringstream name;
            name << "principal axes, signs (" << f[0] << ", " << f[1] << ", " << f[2] << ")";
            hypotheses.emplace_back(h, name.str());
        }
        RegistrationOptions quick = o;
        quick.samples = std::min(o.samples, 2000);
        quick.symmetric = false;
        const auto quick_samples = sample_surface(exam, quick.samples, o.seed + 3);
        struct Scored {
            Rigid t;
            std::string name;
            double score;
        };
        std::vector<Scored> scored;
        for (const auto& [h, name] : hypotheses) {
            const IcpRun r = run_icp(quick_samples, {}, ref_index, nullptr, h, quick, 12, diagonal);
            if (r.result.log.empty()) continue;
            // Score: robust residual spread, penalised by how much of the surface matched.
            const auto pairs = match(quick_samples, r.t, ref_index, quick, std::numeric_limits<double>::infinity());
            std::vector<double> res(pairs.size());
            for (std::size_t i = 0; i < pairs.size(); ++i) res[i] = pairs[i].r;
            const double frac = static_cast<double>(pairs.size()) / static_cast<double>(quick_samples.size());
            const double score = (median_abs(res) + 1e-12 * diagonal) / std::max(frac, 1e-3) / std::max(frac, 1e-3);
            scored.push_back({r.t, name, score});
        }
        if (!scored.empty()) {
            double best = std::numeric_limits<double>::max();
            for (const auto& c : scored) best = std::min(best, c.score);
            // A shape with a symmetry (a sphere, an ellipsoid, a symmetric part) fits equally
            // well in several poses: the robust loss discounts the very damage that tells them
            // apart. Among hypotheses that score within 1.5× of the best, keep the one that
            // turns the examined mesh least, i.e. trust the scan's own placement.
            // note: 1.5× — measured: the four flips of a 12 × 8 × 6 ellipsoid with a bump
            // scored within 0.2 % of each other; the condyle phantom's wrong flips score 260×
            // worse than its right ones.
            const Scored* pick = nullptr;
            std::size_t tied = 0;
            for (const auto& c : scored) {
                if (c.score > 1.5 * best) continue;
                ++tied;
                if (pick == nullptr || Eigen::AngleAxisd(c.t.linear()).angle() < Eigen::AngleAxisd(pick->t.linear()).angle())
                    pick = &c;
            }
            start = pick->t;
            coarse = pick->name;
            if (tied > 1) {
                coarse += " (" + std::to_string(tied) +
                          " hypotheses fit about equally, the shape may be symmetric: kept the smallest rotation)";
            }
        }
    }
    IcpRun run = run_icp(samples, ref_samples, ref_index, &exa_index, start, o, o.max_iterations, diagonal);
    run.result.reference_from_examined = run.t;
    run.result.examined_from_reference = run.t.inverse();
    run.result.coarse = coarse;
    return run.result;
}

Rigid fit_landmarks(const std::vector<Vec3d>& examined, const std::vector<Vec3d>& reference) {
    if (examined.size() != reference.size())
        throw InputError("landmarks: " + std::to_string(examined.size()) + " examined points for " +
                         std::to_string(reference.size()) + " reference points, expected pairs");
    if (examined.size() < 3)
        throw InputError("landmarks: " + std::to_string(examined.size()) + " pair(s), expected at least 3");
    Eigen::Matrix3Xd src(3, examined.size()), dst(3, reference.size());
    for (std::size_t i = 0; i < examined.size(); ++i) {
        src.col(static_cast<Eigen::Index>(i)) = examined[i];
        dst.col(static_cast<Eigen::Index>(i)) = reference[i];
    }
    for (const auto* m : {&src, &dst}) {
        const Eigen::Matrix3Xd centred = m->colwise() - m->rowwise().mean();
        const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(centred);
        const auto sv = svd.singularValues();
        // note: a second singular value below 1e-6 of the first means the points lie on a
        // line (to 1 µm in 1 m): the rotation about that line is undetermined.
        if (!(sv(1) > 1e-6 * sv(0)))
            throw InputError("landmarks: the points are collinear (or coincide), a rotation about their line is undetermined");
    }
    Rigid t = Rigid::Identity();
    t.matrix() = Eigen::umeyama(src, dst, false);
    return t;
}

std::vector<LandmarkPair> read_landmarks(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw IoError("landmarks \"" + path + "\": cannot open");
    nlohmann::json j;
    try {
        in >> j;
    } catch (const nlohmann::json::exception& e) {
        throw InputError("landmarks \"" + path + "\": not valid JSON: " + e.what());
    }
    if (!j.is_object() || !j.contains("pairs") || !j["pairs"].is_array())
        throw InputError("landmarks \"" + path + "\": expected {\"pairs\": [{\"examined\": [x,y,z], \"reference\": [x,y,z]}, …]}");
    std::vector<LandmarkPair> pairs;
    std::size_t i = 0;
    for (const auto& p : j["pairs"]) {
        ++i;
        const std::string where = "landmarks \"" + path + "\": pair " + std::to_string(i);
        if (!p.is_object()) throw InputError(where + ": expected {\"examined\": …, \"reference\": …}, found " + p.type_name());
        auto numbers = [&](const nlohmann::json& v, std::size_t n, const std::string& what, const std::string& shape) {
            if (!v.is_array() || v.size() != n)
                throw InputError(where + ": " + what + " must be " + shape + ", found " +
                                 (v.is_array() ? "an array of " + std::to_string(v.size()) : std::string(v.type_name())));
            std::vector<double> out;
            for (const auto& x : v) {
                if (!x.is_number()) throw InputError(where + ": " + what + " must be " + shape + " (numbers), found a " + x.type_name());
                out.push_back(x.get<double>());
            }
            return out;
        };
        auto side = [&](const char* key) {
            const std::string what = std::string("'") + key + "'";
            if (!p.contains(key)) throw InputError(where + ": no " + what + " (expected [x, y, z] or {\"view\": …, \"pixel\": [u, v]})");
            const auto& s = p[key];
            LandmarkSide out;
            if (s.is_array()) {
                const auto v = numbers(s, 3, what, "[x, y, z]");
                out.point = Vec3d(v[0], v[1], v[2]);
                return out;
            }
            if (!s.is_object() || !s.contains("view") || !s.contains("pixel") || !s["view"].is_object())
                throw InputError(where + ": " + what + " must be [x, y, z] or {\"view\": {\"azimuth\": A, \"elevation\": E, "
                                 "\"size\": N}, \"pixel\": [u, v]}");
            const auto px = numbers(s["pixel"], 2, what + " pixel", "[u, v]");
            out.u = px[0];
            out.v = px[1];
            const auto& view = s["view"];
            auto number = [&](const char* field, bool required, double fallback) {
                if (!view.contains(field)) {
                    if (required) throw InputError(where + ": " + what + " view has no '" + field + "'");
                    return fallback;
                }
                if (!view[field].is_number())
                    throw InputError(where + ": " + what + " view '" + field + "' must be a number, found " + view[field].type_name());
                return view[field].get<double>();
            };
            out.view.azimuth_deg = number("azimuth", true, 0.0);
            out.view.elevation_deg = number("elevation", true, 0.0);
            const double size = number("size", true, 0.0);
            if (!(size >= 1 && size <= 1 << 16 && size == std::floor(size)))
                throw InputError(where + ": " + what + " view 'size' = " + std::to_string(size) + ", expected a whole number of pixels ≥ 1");
            out.view.size = static_cast<int>(size);
            out.view.footprint = number("footprint", false, 0.0);
            if (out.view.footprint < 0) throw InputError(where + ": " + what + " view 'footprint' must be > 0 (or left out)");
            return out;
        };
        pairs.push_back({side("examined"), side("reference")});
    }
    return pairs;
}

std::string to_json(const RegistrationResult& r, const RegistrationOptions& o, const RegistrationSources& sources) {
    auto matrix = [](const Rigid& t) {
        nlohmann::json rows = nlohmann::json::array();
        for (int i = 0; i < 4; ++i) rows.push_back({t(i, 0), t(i, 1), t(i, 2), t(i, 3)});
        return rows;
    };
    nlohmann::json log = nlohmann::json::array();
    for (const auto& l : r.log)
        log.push_back({{"iteration", l.iteration}, {"cost", l.cost}, {"rms", l.rms}, {"loss_scale", l.loss_scale},
                       {"overlap", l.overlap}, {"rotation_step_deg", l.rotation_step_deg},
                       {"translation_step", l.translation_step}});
    auto vec = [](const Vec3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
    nlohmann::json roi;
    switch (o.roi.shape) {
        case RegistrationRoi::Shape::None: roi = {{"shape", "none"}}; break;
        case RegistrationRoi::Shape::Sphere:
            roi = {{"shape", "sphere"}, {"center", vec(o.roi.center)}, {"radius", o.roi.radius}};
            break;
        case RegistrationRoi::Shape::Box: roi = {{"shape", "box"}, {"min", vec(o.roi.min)}, {"max", vec(o.roi.max)}}; break;
        case RegistrationRoi::Shape::VertexMask: {
            const auto on = std::count_if(o.roi.vertex_mask.begin(), o.roi.vertex_mask.end(), [](std::uint8_t m) { return m != 0; });
            roi = {{"shape", "vertex_mask"}, {"file", sources.roi_mask_file}, {"property", sources.roi_mask_property},
                   {"vertices", o.roi.vertex_mask.size()}, {"masked_vertices", on}};
            break;
        }
    }
    const nlohmann::json initial = o.initial ? matrix(*o.initial) : nlohmann::json(nullptr);
    const Eigen::AngleAxisd aa(Eigen::Matrix3d(r.reference_from_examined.linear()));
    const nlohmann::json j = {
        {"reference_from_examined", matrix(r.reference_from_examined)},
        {"examined_from_reference", matrix(r.examined_from_reference)},
        {"rotation_deg", aa.angle() / kDeg},
        {"rotation_axis", {aa.axis().x(), aa.axis().y(), aa.axis().z()}},
        {"translation", {r.reference_from_examined.translation().x(), r.reference_from_examined.translation().y(),
                         r.reference_from_examined.translation().z()}},
        {"rms", r.rms},
        {"inlier_fraction", r.inlier_fraction},
        {"overlap", r.overlap},
        {"iterations", r.iterations},
        {"converged", r.converged},
        {"termination", r.termination},
        {"termination_detail", r.termination_detail},
        {"coarse", r.coarse},
        {"options", {{"loss", to_string(o.loss)}, {"samples", o.samples}, {"max_iterations", o.max_iterations},
                     {"max_normal_angle_deg", o.max_normal_angle_deg}, {"symmetric", o.symmetric},
                     {"rotation_tolerance_deg", o.rotation_tolerance_deg},
                     {"translation_tolerance", o.translation_tolerance}, {"cost_tolerance", o.cost_tolerance},
                     {"min_overlap", o.min_overlap}, {"overlap_distance", o.overlap_distance},
                     {"anneal", {o.anneal_start, o.anneal_end}}, {"seed", o.seed},
                     {"roi", roi}, {"initial", initial}, {"init_file", sources.init_file},
                     {"landmarks_file", sources.landmarks_file}}},
        {"log", log},
    };
    return j.dump(2) + "\n";
}

Rigid read_fit(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw IoError("fit \"" + path + "\": cannot open");
    nlohmann::json j;
    try {
        in >> j;
    } catch (const nlohmann::json::exception& e) {
        throw InputError("fit \"" + path + "\": not valid JSON: " + e.what());
    }
    const auto& m = j.contains("reference_from_examined") ? j["reference_from_examined"] : nlohmann::json();
    if (!m.is_array() || m.size() != 4)
        throw InputError("fit \"" + path + "\": expected \"reference_from_examined\" as a 4×4 array of rows");
    Rigid t = Rigid::Identity();
    for (int r = 0; r < 4; ++r) {
        if (!m[static_cast<std::size_t>(r)].is_array() || m[static_cast<std::size_t>(r)].size() != 4)
            throw InputError("fit \"" + path + "\": row " + std::to_string(r + 1) + " of reference_from_examined is not 4 numbers");
        for (int c = 0; c < 4; ++c) t(r, c) = m[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)].get<double>();
    }
    const Eigen::Matrix3d rot = t.linear();
    // note: 1e-6 tolerates the rounding of a matrix printed with ~10 digits.
    if (!(rot.transpose() * rot).isApprox(Eigen::Matrix3d::Identity(), 1e-6) || std::abs(rot.determinant() - 1) > 1e-6)
        throw InputError("fit \"" + path + "\": reference_from_examined is not a rigid motion (rotation part not orthonormal)");
    return t;
}

}  // namespace glint
