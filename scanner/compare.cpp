#include "scanner/compare.h"

#include "mesh/error.h"
#include "mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace glint {

namespace {

bool covered(const FrameView& f, std::size_t i, float min_coverage) {
    return f.primitive[i] != kNoPrimitive && f.coverage[i] >= min_coverage;
}

}  // namespace

FrameView frame_view(const Frame& f) {
    return {f.width, f.height, f.normal, f.primitive_id, f.depth, f.coverage};
}

FrameView frame_view(const FrameRows& r) {
    return {r.width, r.height, r.normal, r.primitive_id, r.depth, r.coverage};
}

void compare_pixels(const FrameView& ref, const FrameView& exa, const CompareOptions& options,
                    std::span<float> angle_deg, std::span<float> signed_depth,
                    std::span<std::uint8_t> silhouette) {
    const std::size_t n =
        static_cast<std::size_t>(ref.width) * static_cast<std::size_t>(ref.height);
    GLINT_ASSERT(ref.normal.size() == 3 * n && exa.normal.size() == 3 * n,
                 "normal planes of wrong size");
    GLINT_ASSERT(angle_deg.size() == n && signed_depth.size() == n && silhouette.size() == n,
                 "deviation maps of wrong size");
    for (std::size_t i = 0; i < n; ++i) {
        angle_deg[i] = signed_depth[i] = kNaN;
        silhouette[i] = static_cast<std::uint8_t>(Silhouette::Same);
        const bool in_ref = ref.primitive[i] != kNoPrimitive && ref.coverage[i] > 0.0f;
        const bool in_exa = exa.primitive[i] != kNoPrimitive && exa.coverage[i] > 0.0f;
        if (in_ref != in_exa) {
            // note: a pixel half covered in one frame and empty in the other is an edge
            // shift of less than a pixel, not a silhouette change; only fully covered count.
            if (in_ref && covered(ref, i, options.min_coverage))
                silhouette[i] = static_cast<std::uint8_t>(Silhouette::ReferenceOnly);
            else if (in_exa && covered(exa, i, options.min_coverage))
                silhouette[i] = static_cast<std::uint8_t>(Silhouette::ExaminedOnly);
            continue;
        }
        if (!covered(ref, i, options.min_coverage) || !covered(exa, i, options.min_coverage))
            continue;
        const double dot = ref.normal[3 * i] * exa.normal[3 * i] +
                           ref.normal[3 * i + 1] * exa.normal[3 * i + 1] +
                           ref.normal[3 * i + 2] * exa.normal[3 * i + 2];
        const double na = std::sqrt(ref.normal[3 * i] * ref.normal[3 * i] +
                                    ref.normal[3 * i + 1] * ref.normal[3 * i + 1] +
                                    ref.normal[3 * i + 2] * ref.normal[3 * i + 2]);
        const double nb = std::sqrt(exa.normal[3 * i] * exa.normal[3 * i] +
                                    exa.normal[3 * i + 1] * exa.normal[3 * i + 1] +
                                    exa.normal[3 * i + 2] * exa.normal[3 * i + 2]);
        if (!(na > 0 && nb > 0)) continue;
        const double c = std::clamp(dot / (na * nb), -1.0, 1.0);
        // note: acos loses precision near 0°; atan2 of |a×b| and a·b would be better, but at
        // float normals the floor is ~0.02° either way, far below any threshold used.
        angle_deg[i] = static_cast<float>(std::acos(c) * 180.0 / std::numbers::pi);
        signed_depth[i] = ref.depth[i] - exa.depth[i];
    }
}

void summarise(DeviationMap& d) {
    d.compared = d.reference_only = d.examined_only = 0;
    d.max_angle_deg = 0.0;
    double sum = 0.0;
    for (std::size_t i = 0; i < d.angle_deg.size(); ++i) {
        if (d.silhouette[i] == static_cast<std::uint8_t>(Silhouette::ReferenceOnly))
            ++d.reference_only;
        if (d.silhouette[i] == static_cast<std::uint8_t>(Silhouette::ExaminedOnly))
            ++d.examined_only;
        const float angle = d.angle_deg[i];
        if (std::isnan(angle)) continue;
        ++d.compared;
        sum += angle;
        d.max_angle_deg = std::max(d.max_angle_deg, static_cast<double>(angle));
    }
    d.mean_angle_deg = d.compared ? sum / static_cast<double>(d.compared) : 0.0;
}

DeviationMap compare_frames(const FrameView& ref, const FrameView& exa,
                            const CompareOptions& options) {
    if (ref.width != exa.width || ref.height != exa.height)
        throw InputError("frames differ in size: reference " + std::to_string(ref.width) + "x" +
                         std::to_string(ref.height) + ", examined " + std::to_string(exa.width) +
                         "x" + std::to_string(exa.height));
    const std::size_t n =
        static_cast<std::size_t>(ref.width) * static_cast<std::size_t>(ref.height);
    DeviationMap d;
    d.width = ref.width;
    d.height = ref.height;
    d.angle_deg.resize(n);
    d.signed_depth.resize(n);
    d.silhouette.resize(n);
    compare_pixels(ref, exa, options, d.angle_deg, d.signed_depth, d.silhouette);
    summarise(d);
    return d;
}

}  // namespace glint
