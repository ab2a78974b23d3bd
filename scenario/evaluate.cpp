#include "scenario/evaluate.h"

#include "mesh/error.h"

#include <limits>

namespace glint {

DetectionScore score_detection(const Mesh& reference, const std::vector<std::int32_t>& detected,
                               const std::vector<std::uint8_t>& truth,
                               const std::vector<Region>& regions) {
    const std::size_t n = reference.vertex_count();
    GLINT_ASSERT(detected.size() == n && truth.size() == n, "score inputs do not match the mesh");
    DetectionScore s;
    const auto areas = vertex_areas(reference);
    Vec3d truth_centroid = Vec3d::Zero();
    double truth_area = 0.0;
    for (std::size_t v = 0; v < n; ++v) {
        const bool d = detected[v] != 0;
        const bool t = truth[v] != 0;
        s.true_positive += d && t;
        s.false_positive += d && !t;
        s.false_negative += !d && t;
        s.truth_vertices += t;
        if (t) {
            truth_centroid += areas[v] * reference.positions[v].cast<double>();
            truth_area += areas[v];
        }
    }
    const auto tp = static_cast<double>(s.true_positive);
    const auto fp = static_cast<double>(s.false_positive);
    const auto fn = static_cast<double>(s.false_negative);
    s.precision = tp + fp > 0 ? tp / (tp + fp) : 1.0;
    s.recall = tp + fn > 0 ? tp / (tp + fn) : 1.0;
    s.f1 = s.precision + s.recall > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0.0;
    s.iou = tp + fp + fn > 0 ? tp / (tp + fp + fn) : 1.0;
    if (truth_area > 0 && !regions.empty()) {
        truth_centroid /= truth_area;
        double best = std::numeric_limits<double>::max();
        for (const auto& r : regions) best = std::min(best, (r.centroid - truth_centroid).norm());
        s.centroid_error = best;
    }
    return s;
}

PoseError pose_error(const Rigid& estimated, const Rigid& truth, double estimated_scale,
                     double true_scale) {
    const Rigid delta = truth.inverse() * estimated;
    return {rotation_angle_deg(delta), delta.translation().norm(),
            std::abs(estimated_scale - true_scale)};
}

}  // namespace glint
