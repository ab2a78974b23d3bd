#include "registration/icp.h"

#include "mesh/error.h"
#include "registration/closest_point.h"
#include "registration/detail/coarse.h"
#include "registration/detail/icp_core.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

namespace glint {

namespace {
// The examined surface's area, in reference areas, above which the reference is matched on it.
constexpr double kTurnRoles = 1.5;

// x ↦ rigid(scale · x): the fitted motion with the examined surface's scale about the origin.
struct Similarity {
    Rigid rigid = Rigid::Identity();
    double scale = 1.0;

    [[nodiscard]] Similarity inverse() const {
        // x = R s p + T  ⇒  p = Rᵀ((1/s) x) − (1/s) Rᵀ T.
        Similarity out;
        out.rigid.linear() = rigid.linear().transpose();
        out.rigid.translation() = -(rigid.linear().transpose() * rigid.translation()) / scale;
        out.scale = 1.0 / scale;
        return out;
    }
};

// An ICP run's motion (samples scaled about its centre, then moved) about the origin, applied to
// a surface first scaled by `initial`: x ↦ t(c + S(s0 p − c)) = R(S s0 p) + R(1 − S)c + T.
Similarity similarity_of(const detail::IcpRun& run, double initial) {
    Similarity out;
    out.rigid = run.t;
    out.rigid.translation() += run.t.linear() * ((1.0 - run.scale) * run.center);
    out.scale = run.scale * initial;
    return out;
}

void set_motion(RegistrationResult& r, const Similarity& s) {
    r.reference_from_examined = s.rigid;
    r.examined_from_reference = s.rigid.inverse();
    r.examined_scale = s.scale;
}

// The examined surface at `initial` × its size (a copy only when it differs from 1).
const Mesh& scaled_examined(const Mesh& exam, double initial, std::optional<Mesh>& storage) {
    if (initial == 1.0) return exam;
    storage = exam;
    for (auto& p : storage->positions) p *= static_cast<float>(initial);
    return *storage;
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

void RegistrationOptions::validate() const {
    if (samples < 50) throw OptionError("samples", samples, "must be ≥ 50");
    if (max_iterations < 1) throw OptionError("max_iterations", max_iterations, "must be ≥ 1");
    if (inner_iterations < 1)
        throw OptionError("inner_iterations", inner_iterations, "must be ≥ 1");
    if (!(anneal_end > 0) || anneal_start < anneal_end)
        throw OptionError("anneal", anneal_start, "needs start ≥ end > 0");
    if (!(max_normal_angle_deg > 0 && max_normal_angle_deg <= 180))
        throw OptionError("max_normal_angle", max_normal_angle_deg, "must be in (0, 180] degrees");
    if (!(cost_tolerance >= 0)) throw OptionError("cost_tolerance", cost_tolerance, "must be ≥ 0");
    if (!(min_overlap >= 0 && min_overlap <= 1))
        throw OptionError("min_overlap", min_overlap, "must be in [0, 1]");
    if (!(overlap_distance > 0))
        throw OptionError("overlap_distance", overlap_distance, "must be > 0");
    if (!(initial_scale > 0) || !std::isfinite(initial_scale))
        throw OptionError("initial_scale", initial_scale, "must be a finite number > 0");
}

RegistrationResult register_meshes(const Mesh& reference, const Mesh& examined,
                                   const RegistrationOptions& o,
                                   const std::shared_ptr<const SurfaceIndex>& reference_index) {
    o.validate();
    if (reference.triangles.empty() || examined.triangles.empty())
        throw InputError("registration: both meshes need triangles");
    if (o.roi && o.roi->shape == Roi::Shape::VertexMask &&
        o.roi->vertex_mask.size() != reference.vertex_count())
        throw InputError("registration: the ROI vertex mask has " +
                         std::to_string(o.roi->vertex_mask.size()) +
                         " entries, the reference has " + std::to_string(reference.vertex_count()) +
                         " vertices");
    if (o.roi) {
        std::size_t inside = 0;
        for (std::size_t v = 0; v < reference.vertex_count(); ++v)
            inside += o.roi->contains(v, reference.positions[v].cast<double>());
        if (inside == 0)
            throw InputError("registration: the ROI " + to_string(*o.roi) +
                             " contains no vertex of the reference mesh");
    }
    const ClosestPointIndex ref_index = reference_index
                                            ? ClosestPointIndex(reference, reference_index)
                                            : ClosestPointIndex::borrowing(reference);
    // The examined samples carry vertex normals (angle-weighted ones computed when the mesh has
    // none). Its closest-point index only for a symmetric fit, the one that queries it: the
    // BVH of a 2M-triangle mesh takes about half a second to build.
    std::optional<Mesh> with_normals, at_initial_scale;
    const Mesh& exam = scaled_examined(detail::with_vertex_normals(examined, with_normals),
                                       o.initial_scale, at_initial_scale);
    std::optional<ClosestPointIndex> exa_index;
    if (o.symmetric) exa_index.emplace(ClosestPointIndex::borrowing(exam));
    const double diagonal = std::max(bounds(reference).diagonal(), bounds(exam).diagonal());
    const auto samples = detail::sample_surface(exam, o.samples, o.seed);
    const auto ref_samples =
        o.symmetric ? detail::sample_surface(ref_index.mesh(), o.samples / 2, o.seed + 1)
                    : std::vector<detail::Sample>{};

    Rigid start = o.initial.value_or(Rigid::Identity());
    std::string coarse = o.initial ? "given initial pose" : "identity";
    if (o.coarse && !o.initial) {
        const CoarseAlignment c = detail::coarse_align(ref_index, exam, samples, o, diagonal);
        start = c.reference_from_examined;
        coarse = c.description;
    }
    detail::IcpRun run =
        detail::run_icp(samples, ref_samples, ref_index, exa_index ? &*exa_index : nullptr, start,
                        o, o.max_iterations, diagonal);
    set_motion(run.result, similarity_of(run, o.initial_scale));
    const detail::ScaleTrend trend = o.measure_scale
                                         ? detail::scale_trend(samples, ref_index, run, o, diagonal)
                                         : detail::ScaleTrend{};
    run.result.scale_trend = trend.scale;
    run.result.scale_trend_uncertainty = trend.uncertainty;
    if (o.fit_scale) run.result.scale_uncertainty = trend.uncertainty * run.result.examined_scale;
    run.result.coarse = coarse;
    // note: an examined surface that covers far more than the reference (a reference cropped
    // around one condyle against the whole jaw, issue 53) leaves most of its samples with no
    // reference surface near them: the fit found "overlap 0.018 < 0.2". When the fit above
    // failed so, the roles turn: the reference's samples are matched on the examined surface
    // (what the reference shows, the examined surface covers) and the motion found is
    // inverted; the better of the two is kept. Not with an ROI (it selects reference surface
    // to match on) nor the symmetric fit (it matches both ways already).
    const double reference_area = surface_area(reference), examined_area = surface_area(exam);
    if (run.result.converged || o.roi || o.symmetric ||
        !(examined_area > kTurnRoles * reference_area))
        return run.result;
    const Mesh& ref = ref_index.mesh();
    const ClosestPointIndex onto = ClosestPointIndex::borrowing(exam);
    const auto ref_samples_only = detail::sample_surface(ref, o.samples, o.seed);
    Rigid turned_start = o.initial ? o.initial->inverse() : Rigid::Identity();
    std::string turned_coarse = o.initial ? "given initial pose" : "identity";
    if (o.coarse && !o.initial) {
        const CoarseAlignment c = detail::coarse_align(onto, ref, ref_samples_only, o, diagonal);
        turned_start = c.reference_from_examined;  // here: examined from reference
        turned_coarse = c.description;
    }
    detail::IcpRun turned = detail::run_icp(ref_samples_only, {}, onto, nullptr, turned_start, o,
                                            o.max_iterations, diagonal);
    if (!turned.result.converged && turned.result.overlap <= run.result.overlap) return run.result;
    // The turned run scaled and moved the reference onto the (initially scaled) examined surface.
    Similarity exam_from_ref = similarity_of(turned, 1.0);
    Similarity ref_from_exam = exam_from_ref.inverse();
    ref_from_exam.scale *= o.initial_scale;
    set_motion(turned.result, ref_from_exam);
    // The trend measured the turned way round is the reference's scale against the examined.
    const detail::ScaleTrend turned_trend =
        o.measure_scale ? detail::scale_trend(ref_samples_only, onto, turned, o, diagonal)
                        : detail::ScaleTrend{};
    turned.result.scale_trend = 1.0 / (1.0 + turned_trend.scale) - 1.0;
    turned.result.scale_trend_uncertainty = turned_trend.uncertainty;
    if (o.fit_scale)
        turned.result.scale_uncertainty = turned_trend.uncertainty * turned.result.examined_scale;
    char why[200];
    std::snprintf(why, sizeof why,
                  "; the reference's samples matched on the examined surface (it covers %.1f× "
                  "the reference's area; matched the other way, overlap %.3f)",
                  examined_area / reference_area, run.result.overlap);
    turned.result.coarse = turned_coarse + why;
    turned.result.reference_on_examined = true;
    return turned.result;
}

}  // namespace glint
