#include "report/asymmetry_run.h"

#include "mesh/error.h"
#include "report/asymmetry_json.h"

#include <utility>

namespace glint {

AsymmetryOptions take_asymmetry_options(AnalysisOptions& analysis,
                                        std::optional<SymmetryPlane> given_plane) {
    AsymmetryOptions options;
    options.plane.registration = analysis.fit.registration;
    options.given_plane = given_plane;
    analysis.fit = FitOptions{};  // the mirror is made in place: no fit
    return options;
}

AsymmetryInspection inspect_asymmetry(const Mesh& mesh, AsymmetryPlane plane,
                                      InspectOptions options, RunRecord record,
                                      const Orientation& orientation,
                                      const AnalysisObserver& observer) {
    GLINT_ASSERT(!plane.mirror.triangles.empty(), "inspect_asymmetry needs a plausible plane");
    RunInput mirror = mesh_run_input("examined", std::move(plane.mirror),
                                     "mirror image of the reference about its symmetry plane");
    record.add(mirror);
    AsymmetryInspection out;
    // The floors are the surface's natural asymmetry (decision.h natural_floors).
    options.analysis.decision.natural_floors = true;
    options.addition = [&](const AnalysisResult& r) {
        out.findings = pair_findings(mesh, plane.plane.plane, r);
        out.json = asymmetry_json(plane.plane, out.findings, orientation, r.unit);
        return ReportAddition{.scalars = {{"asymmetry{unit}", out.findings.field}},
                              .key = "asymmetry",
                              .json = out.json,
                              .mirror = mirror_pictures(plane.plane)};
    };
    out.inspection = inspect(mesh, std::move(mirror.mesh), options, record, observer);
    // The analysis warns that no fit was asked for; the mirror is in place: no warning.
    out.warnings = out.inspection.analysis.warnings;
    std::erase_if(out.warnings,
                  [](const std::string& w) { return w.starts_with("no fit requested"); });
    return out;
}

}  // namespace glint
