// Scoring a detected damage mask against ground truth, per reference vertex.
//
// Every vertex counts, seen or not: a damaged vertex that no view saw is a false negative
// (unseen is never undamaged), so recall drops when coverage is poor.
#pragma once

#include "decision/regions.h"
#include "mesh/geometry.h"
#include "mesh/mesh.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace glint {

struct DetectionScore {
    std::size_t true_positive = 0;
    std::size_t false_positive = 0;
    std::size_t false_negative = 0;
    std::size_t truth_vertices = 0;
    double precision = 0.0;  ///< TP / (TP + FP); 1 when nothing was detected and nothing is there
    double recall = 0.0;     ///< TP / (TP + FN); 1 when there is nothing to find
    double f1 = 0.0;
    double iou = 0.0;  ///< TP / (TP + FP + FN); 1 when both are empty
    /// Distance from the truth's area-weighted centroid to the nearest region centroid
    /// (nullopt when either is empty).
    std::optional<double> centroid_error;
};

/// `detected[v]` = region id (0 = none), `truth[v]` = 1 when damaged.
[[nodiscard]] DetectionScore score_detection(const Mesh& reference,
                                             const std::vector<std::int32_t>& detected,
                                             const std::vector<std::uint8_t>& truth,
                                             const std::vector<Region>& regions);

struct PoseError {
    double rotation_deg = 0.0;
    double translation = 0.0;  ///< mesh units, at the origin of the reference frame
    double scale = 0.0;        ///< |estimated − true| examined scale (a similarity fit)
};

/// Error of an estimated reference_from_examined (after scaling the examined by
/// `estimated_scale`) against the truth.
[[nodiscard]] PoseError pose_error(const Rigid& estimated, const Rigid& truth,
                                   double estimated_scale = 1.0, double true_scale = 1.0);

}  // namespace glint
