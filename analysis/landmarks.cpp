#include "analysis/landmarks.h"

#include "mesh/error.h"

#include <sstream>

namespace glint {

View pick_view(const Mesh& mesh, const LandmarkView& view) {
    ViewSpec spec;
    spec.azimuth_deg = view.azimuth_deg;
    spec.elevation_deg = view.elevation_deg;
    spec.width = spec.height = view.size;
    if (view.footprint > 0) {
        spec.zoom = ZoomKind::Footprint;
        spec.zoom_value = view.footprint;
    }
    return make_view(mesh, spec);
}

ResolvedLandmarks resolve_landmarks(const std::vector<LandmarkPair>& pairs,
                                    const ClosestPointIndex& reference,
                                    const ClosestPointIndex& examined, const std::string& source) {
    ResolvedLandmarks out;
    auto resolve = [&](const LandmarkSide& side, const ClosestPointIndex& index, std::size_t pair,
                       const char* name) {
        if (side.point) return *side.point;
        const View view = pick_view(index.mesh(), side.view);
        const RayHit hit = pick(index, view.camera, side.u, side.v);
        if (!hit.hit) {
            std::ostringstream s;
            s << source << ": pair " << pair + 1 << ": the " << name << " pixel (" << side.u << ", "
              << side.v << ") of the view azimuth " << side.view.azimuth_deg << "°, elevation "
              << side.view.elevation_deg << "°, size " << side.view.size << " shows no surface";
            throw InputError(s.str());
        }
        return hit.point;
    };
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        out.examined.push_back(resolve(pairs[i].examined, examined, i, "examined"));
        out.reference.push_back(resolve(pairs[i].reference, reference, i, "reference"));
    }
    return out;
}

}  // namespace glint
