#include "decision/detail/evidence_scale.h"

#include "decision/detail/fused_rule.h"
#include "mesh/error.h"

#include <Eigen/Dense>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <thread>
#include <unordered_map>

namespace glint::detail {

namespace {

// note: a fit needs a few neighbours beyond the plane's three unknowns; with fewer the
// vertex keeps its own distance and no tilt.
constexpr int kMinFitVertices = 6;

// The vertices a fit may use: seen, with an examined surface and a finite distance.
std::vector<std::uint8_t> usable(const DecisionEvidence& e) {
    const auto& d = *e.distance;
    std::vector<std::uint8_t> u(d.size(), 0);
    for (std::size_t v = 0; v < d.size(); ++v)
        u[v] = e.coverage->seen[v] && e.atlas->missing[v] <= 0.5f && std::isfinite(d[v]);
    return u;
}

// One vertex's fit over the connected ball of radius r (breadth first through mesh edges).
class BallFit {
  public:
    BallFit(const Mesh& mesh, const Adjacency& adj, const DecisionEvidence& e,
            const std::vector<std::uint8_t>& use, double radius)
        : mesh_(mesh),
          adj_(adj),
          e_(e),
          use_(use),
          r2_(radius * radius),
          inv_two_sigma2_(2.0 / (radius * radius)),
          stamp_(mesh.vertex_count(), -1) {}

    /// The fitted plane at v: its value there and its gradient (mesh units per unit, in the
    /// tangent plane); the gradient is zero where the fit fell back to v's own distance.
    void fit(std::size_t v, ScaledEvidence& out, Eigen::Vector3d* gradient = nullptr) {
        if (gradient) gradient->setZero();
        const Eigen::Vector3d p = mesh_.positions[v].cast<double>();
        const Eigen::Vector3d n = mesh_.normals[v].cast<double>().normalized();
        const Eigen::Vector3d t1 = n.unitOrthogonal();
        const Eigen::Vector3d t2 = n.cross(t1);
        Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
        Eigen::Vector3d b = Eigen::Vector3d::Zero();
        double tol = 0.0, weight = 0.0, weight2 = 0.0;
        int used = 0;
        queue_.assign(1, static_cast<std::uint32_t>(v));
        stamp_[v] = static_cast<std::int64_t>(v);
        for (std::size_t head = 0; head < queue_.size(); ++head) {
            const std::uint32_t u = queue_[head];
            const Eigen::Vector3d q = mesh_.positions[u].cast<double>() - p;
            if (use_[u]) {
                const double w = std::exp(-q.squaredNorm() * inv_two_sigma2_);
                const Eigen::Vector3d x(1.0, q.dot(t1), q.dot(t2));
                a += w * x * x.transpose();
                b += w * x * static_cast<double>((*e_.distance)[u]);
                if (e_.tolerance) tol += w * static_cast<double>((*e_.tolerance)[u]);
                weight += w;
                weight2 += w * w;
                ++used;
            }
            for (std::uint32_t k = adj_.offset[u]; k < adj_.offset[u + 1]; ++k) {
                const std::uint32_t w = adj_.index[k];
                if (stamp_[w] == static_cast<std::int64_t>(v)) continue;
                stamp_[w] = static_cast<std::int64_t>(v);
                if ((mesh_.positions[w].cast<double>() - p).squaredNorm() <= r2_)
                    queue_.push_back(w);
            }
        }
        const bool has_tolerance = e_.tolerance && e_.tolerance->size() == use_.size();
        out.tolerance[v] = has_tolerance ? (*e_.tolerance)[v] : 0.0f;
        out.distance[v] = (*e_.distance)[v];
        out.tilt_deg[v] = 0.0f;
        if (used < kMinFitVertices) return;
        const Eigen::Vector3d c = a.ldlt().solve(b);
        if (!c.allFinite()) return;
        out.distance[v] = static_cast<float>(c[0]);
        if (gradient) *gradient = c[1] * t1 + c[2] * t2;
        out.tilt_deg[v] =
            static_cast<float>(std::atan(std::hypot(c[1], c[2])) * 180.0 / std::numbers::pi);
        // The tolerance of the fit's value: each facet's chord lies off the surface by its own
        // amount and sign, so over the disc they average like noise over the fit's effective
        // number of vertices (Σw)²/Σw²; the floors, measured on the pair at this scale, hold
        // what is left of them on the undamaged majority.
        if (has_tolerance && weight > 0)
            out.tolerance[v] = static_cast<float>(tol / weight * std::sqrt(weight2) / weight);
    }

  private:
    const Mesh& mesh_;
    const Adjacency& adj_;
    const DecisionEvidence& e_;
    const std::vector<std::uint8_t>& use_;
    double r2_;
    double inv_two_sigma2_;  // Gaussian weights, σ = r/2: 1/(2σ²) = 2/r²
    std::vector<std::int64_t> stamp_;
    std::vector<std::uint32_t> queue_;
};

}  // namespace

ScaledEvidence scaled_evidence(const Mesh& reference, const DecisionEvidence& e, double radius,
                               std::size_t stride) {
    GLINT_ASSERT(e.distance && e.distance->size() == reference.vertex_count(),
                 "scaled evidence without a distance per vertex");
    GLINT_ASSERT(reference.has_normals(), "scaled evidence needs the reference's normals");
    const std::size_t n = reference.vertex_count();
    stride = std::max<std::size_t>(stride, 1);
    const float unset = stride > 1 ? std::numeric_limits<float>::quiet_NaN() : 0.0f;
    ScaledEvidence out{.radius = radius,
                       .distance = std::vector<float>(n, unset),
                       .tolerance = std::vector<float>(n, unset),
                       .tilt_deg = std::vector<float>(n, unset)};
    const Adjacency adj = adjacency(reference);
    const std::vector<std::uint8_t> use = usable(e);
    // One fit state per interleaved share of the vertices, on oneTBB's workers: a worker that
    // cannot be started leaves its share to the others (a std::thread that could not start
    // ended the run in std::terminate from the pool's destructor).
    const std::size_t shares = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
    tbb::parallel_for(std::size_t{0}, shares, [&](std::size_t t) {
        BallFit fit(reference, adj, e, use, radius);
        for (std::size_t v = t * stride; v < n; v += shares * stride) fit.fit(v, out);
    });
    return out;
}

ScaledEvidence sparse_scaled_evidence(const Mesh& reference, const DecisionEvidence& e,
                                      double radius) {
    GLINT_ASSERT(e.distance && e.distance->size() == reference.vertex_count(),
                 "scaled evidence without a distance per vertex");
    GLINT_ASSERT(reference.has_normals(), "scaled evidence needs the reference's normals");
    GLINT_ASSERT(radius > 0, "sparse scaled evidence needs a radius");
    const std::size_t n = reference.vertex_count();
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    ScaledEvidence out{.radius = radius,
                       .distance = std::vector<float>(n, kNaN),
                       .tolerance = std::vector<float>(n, kNaN),
                       .tilt_deg = std::vector<float>(n, kNaN)};
    if (n == 0) return out;
    const std::vector<std::uint8_t> use = usable(e);
    // One usable vertex per cell and facing: 20 bits per axis (a million cells across), 3 for
    // the facing.
    Eigen::Vector3f lo = reference.positions[0];
    for (const auto& p : reference.positions) lo = lo.cwiseMin(p);
    const double cell = 0.25 * radius;
    std::unordered_map<std::uint64_t, std::uint32_t> first;
    std::vector<std::uint32_t> chosen;
    for (std::size_t v = 0; v < n; ++v) {
        if (!use[v]) continue;
        const Eigen::Vector3f& nv = reference.normals[v];
        Eigen::Index axis = 0;
        nv.cwiseAbs().maxCoeff(&axis);
        std::uint64_t key = static_cast<std::uint64_t>(2 * axis + (nv[axis] < 0 ? 1 : 0));
        for (int k = 0; k < 3; ++k) {
            const auto c = static_cast<std::uint64_t>(
                std::clamp((static_cast<double>(reference.positions[v][k]) - lo[k]) / cell, 0.0,
                           double((1 << 20) - 1)));
            key = (key << 20) | c;
        }
        if (first.emplace(key, static_cast<std::uint32_t>(v)).second)
            chosen.push_back(static_cast<std::uint32_t>(v));
    }
    const Adjacency adj = adjacency(reference);
    std::vector<Eigen::Vector3d> gradient(chosen.size());
    const std::size_t shares = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
    tbb::parallel_for(std::size_t{0}, shares, [&](std::size_t t) {
        BallFit fit(reference, adj, e, use, radius);
        for (std::size_t k = t; k < chosen.size(); k += shares)
            fit.fit(chosen[k], out, &gradient[k]);
    });
    // Every other vertex: the plane of the nearest fitted vertex through mesh edges (breadth
    // first from all of them at once), evaluated at its own position; a vertex no fitted one
    // reaches keeps NaN.
    std::vector<std::uint32_t> source(n, std::numeric_limits<std::uint32_t>::max());
    std::vector<std::uint32_t> queue;
    queue.reserve(n);
    for (std::size_t k = 0; k < chosen.size(); ++k) {
        source[chosen[k]] = static_cast<std::uint32_t>(k);
        queue.push_back(chosen[k]);
    }
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::uint32_t u = queue[head];
        const std::uint32_t k = source[u];
        const std::uint32_t c = chosen[k];
        for (std::uint32_t a = adj.offset[u]; a < adj.offset[u + 1]; ++a) {
            const std::uint32_t w = adj.index[a];
            if (source[w] != std::numeric_limits<std::uint32_t>::max()) continue;
            source[w] = k;
            const Eigen::Vector3d step =
                (reference.positions[w] - reference.positions[c]).cast<double>();
            out.distance[w] = static_cast<float>(out.distance[c] + gradient[k].dot(step));
            out.tolerance[w] = out.tolerance[c];
            out.tilt_deg[w] = out.tilt_deg[c];
            queue.push_back(w);
        }
    }
    return out;
}

std::vector<double> scale_ladder(const Mesh& reference, double size) {
    std::vector<float> edge;
    edge.reserve(reference.triangle_count());
    for (const auto& t : reference.triangles)
        edge.push_back((reference.positions[t[0]] - reference.positions[t[1]]).norm());
    if (edge.empty()) return {};
    const auto mid = edge.begin() + static_cast<std::ptrdiff_t>(edge.size() / 2);
    std::nth_element(edge.begin(), mid, edge.end());
    const double h = *mid;
    std::vector<double> radii;
    for (const double k : {2.0, 4.0, 8.0, 16.0, 32.0})
        if (k * h <= 0.08 * size) radii.push_back(k * h);
    return radii;
}

}  // namespace glint::detail
