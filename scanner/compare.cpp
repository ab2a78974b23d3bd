#include "scanner/compare.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace glint {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

bool covered(const FrameView& f, std::size_t i, float min_coverage) {
    return f.primitive[i] != kNoPrimitive && f.coverage[i] >= min_coverage;
}

}  // namespace

FrameView frame_view(const Frame& f) {
    return {f.width, f.height, f.normal, f.primitive_id, f.depth, f.coverage};
}

DeviationMap compare_frames(const FrameView& ref, const FrameView& exa, const CompareOptions& options) {
    if (ref.width != exa.width || ref.height != exa.height)
        throw InputError("frames differ in size: reference " + std::to_string(ref.width) + "x" +
                         std::to_string(ref.height) + ", examined " + std::to_string(exa.width) + "x" +
                         std::to_string(exa.height));
    const std::size_t n = static_cast<std::size_t>(ref.width) * static_cast<std::size_t>(ref.height);
    GLINT_ASSERT(ref.normal.size() == 3 * n && exa.normal.size() == 3 * n, "normal planes of wrong size");
    DeviationMap d;
    d.width = ref.width;
    d.height = ref.height;
    d.angle_deg.assign(n, kNaN);
    d.signed_depth.assign(n, kNaN);
    d.silhouette.assign(n, static_cast<std::uint8_t>(Silhouette::Same));
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const bool in_ref = ref.primitive[i] != kNoPrimitive && ref.coverage[i] > 0.0f;
        const bool in_exa = exa.primitive[i] != kNoPrimitive && exa.coverage[i] > 0.0f;
        if (in_ref != in_exa) {
            // note: a pixel half covered in one frame and empty in the other is an edge
            // shift of less than a pixel, not a silhouette change; only fully covered count.
            if (in_ref && covered(ref, i, options.min_coverage)) {
                d.silhouette[i] = static_cast<std::uint8_t>(Silhouette::ReferenceOnly);
                ++d.reference_only;
            } else if (in_exa && covered(exa, i, options.min_coverage)) {
                d.silhouette[i] = static_cast<std::uint8_t>(Silhouette::ExaminedOnly);
                ++d.examined_only;
            }
            continue;
        }
        if (!covered(ref, i, options.min_coverage) || !covered(exa, i, options.min_coverage)) continue;
        const double dot = ref.normal[3 * i] * exa.normal[3 * i] + ref.normal[3 * i + 1] * exa.normal[3 * i + 1] +
                           ref.normal[3 * i + 2] * exa.normal[3 * i + 2];
        const double na = std::sqrt(ref.normal[3 * i] * ref.normal[3 * i] + ref.normal[3 * i + 1] * ref.normal[3 * i + 1] +
                                    ref.normal[3 * i + 2] * ref.normal[3 * i + 2]);
        const double nb = std::sqrt(exa.normal[3 * i] * exa.normal[3 * i] + exa.normal[3 * i + 1] * exa.normal[3 * i + 1] +
                                    exa.normal[3 * i + 2] * exa.normal[3 * i + 2]);
        if (!(na > 0 && nb > 0)) continue;
        const double c = std::clamp(dot / (na * nb), -1.0, 1.0);
        // note: acos loses precision near 0°; atan2 of |a×b| and a·b would be better, but at
        // float normals the floor is ~0.02° either way, far below any threshold used.
        const auto angle = static_cast<float>(std::acos(c) * 180.0 / std::numbers::pi);
        d.angle_deg[i] = angle;
        d.signed_depth[i] = ref.depth[i] - exa.depth[i];
        ++d.compared;
        sum += angle;
        d.max_angle_deg = std::max(d.max_angle_deg, static_cast<double>(angle));
    }
    d.mean_angle_deg = d.compared ? sum / static_cast<double>(d.compared) : 0.0;

    return d;
}

}  // namespace glint
