#include "scanner/fit.h"

#include "mesh/error.h"
#include "registration/closest_point.h"
#include "registration/icp.h"

namespace glint {

FitOutcome fit_examined(const Mesh& reference, const Mesh& examined, const FitRequest& request) {
    FitOutcome out;
    switch (request.mode) {
        case FitRequest::Mode::Identity:
            out.mode = "identity";
            out.json = R"({"mode": "identity", "note": "the meshes were taken as already aligned"})";
            out.warnings.push_back("no fit requested (--fit or --register): the meshes are taken as already aligned");
            break;
        case FitRequest::Mode::Truth: {
            out.mode = "truth";
            out.reference_from_examined = request.truth;
            RegistrationResult r;
            r.reference_from_examined = request.truth;
            r.examined_from_reference = request.truth.inverse();
            r.converged = true;
            r.termination = "known transform (scenario ground truth)";
            out.json = to_json(r, RegistrationOptions{});
            break;
        }
        case FitRequest::Mode::File:
            out.mode = "file";
            out.reference_from_examined = read_fit(request.fit_file.string());
            out.json = R"({"mode": "file", "path": ")" + request.fit_file.string() + "\"}";
            break;
        case FitRequest::Mode::Register: {
            out.mode = "register";
            RegistrationOptions o;
            o.loss = parse_loss(request.loss);
            o.symmetric = request.symmetric;
            if (!request.roi.empty()) o.roi = parse_registration_roi(request.roi);
            const RegistrationResult r = register_meshes(reference, examined, o);
            out.reference_from_examined = r.reference_from_examined;
            out.converged = r.converged;
            out.json = to_json(r, o);
            if (!r.converged) out.warnings.push_back("registration did not converge: " + r.termination_detail);
            break;
        }
    }
    return out;
}

std::vector<float> signed_distances(const Mesh& reference, const Mesh& fitted_examined) {
    const ClosestPointIndex index(fitted_examined);
    std::vector<Vec3d> points(reference.vertex_count());
    for (std::size_t v = 0; v < points.size(); ++v) points[v] = reference.positions[v].cast<double>();
    const auto d = signed_distances(index, points);
    // A reference vertex outside the examined surface (positive) means the examined surface
    // lies inside: a loss. Negate so that negative = loss, as everywhere in the atlas.
    std::vector<float> out(d.size());
    for (std::size_t v = 0; v < d.size(); ++v) out[v] = static_cast<float>(-d[v]);
    return out;
}

}  // namespace glint
