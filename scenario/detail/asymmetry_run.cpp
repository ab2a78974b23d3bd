#include "scenario/detail/asymmetry_run.h"

#include "analysis/asymmetry.h"
#include "mesh/roi.h"
#include "report/asymmetry_json.h"
#include "report/asymmetry_run.h"
#include "report/orientation.h"
#include "scenario/evaluate.h"
#include "volume/volume.h"

#include <nlohmann/json.hpp>

#include <utility>

namespace glint::detail {

PatientSpace reference_space(const Scenario& sc) {
    if (sc.reference.phantom || sc.reference.mesh.empty()) return PatientSpace::Unknown;
    if (is_volume_path(sc.reference.mesh)) return PatientSpace::LPS;
    return space_stated_in(sc.reference.mesh);
}

namespace {

// The plane found on the analysed surface (the examined one, posed), in the reference's frame.
SymmetryPlane in_reference_frame(const SymmetryPlane& plane, const Rigid& reference_from_examined) {
    return plane_through(reference_from_examined * plane.point(),
                         reference_from_examined.linear() * plane.normal);
}

// The record of the reference is the surface analysed: the reference as the scenario derives
// it (damage, noise, re-meshing, motion), with its own counts.
void describe_analysed(const Scenario& sc, const Mesh& mesh, PatientSpace space, InputRecord& in) {
    in.space = to_string(space);
    in.vertices = mesh.vertex_count();
    in.triangles = mesh.triangle_count();
    const bool moved = !sc.pose.matrix().isIdentity();
    if (!sc.damages.empty() || sc.remesh || sc.noise_sigma > 0 || sc.shuffle || moved)
        in.description += std::string(in.description.empty() ? "" : ", ") +
                          "as the scenario derives it ([[damage]], [examined] remesh, shuffle, "
                          "noise, pose)";
}

AsymmetryOutcome plane_outcome(const Scenario& sc, const ScenarioMeshes& meshes,
                               const SymmetryPlaneResult& r) {
    AsymmetryOutcome o;
    o.plausible = r.plausible;
    o.verdict = r.verdict;
    o.plane = in_reference_frame(r.plane, meshes.true_reference_from_examined);
    if (const auto& expected = sc.expect.asymmetry.plane) {
        const auto [angle, offset] = plane_difference(o.plane, *expected);
        o.plane_angle_deg = angle;
        o.plane_offset = offset;
    }
    return o;
}

// The findings' own regions (the side each is shown on) against the damage labels the
// analysed surface carries (mesh/damage.h), when it carries them.
void score_findings(const Mesh& mesh, const ZoomDecision& z0, const AsymmetryFindings& f,
                    ScenarioOutcome& out) {
    const std::size_t n = mesh.vertex_count();
    if (mesh.labels.size() != n || z0.regions.region_of_vertex.size() != n) return;
    std::vector<std::uint8_t> truth(n);
    for (std::size_t v = 0; v < n; ++v) truth[v] = mesh.labels[v] != 0;
    std::vector<std::int32_t> detected(n, 0);
    std::vector<Region> shown;
    for (const AsymmetryFinding& finding : f.findings) {
        for (std::size_t v = 0; v < n; ++v)
            if (z0.regions.region_of_vertex[v] == finding.region) detected[v] = finding.region;
        for (const Region& r : z0.regions.regions)
            if (r.id == finding.region) shown.push_back(r);
    }
    out.score = score_detection(mesh, detected, truth, shown);
}

}  // namespace

std::vector<Region> run_asymmetry(const Scenario& sc, const ScenarioRunOptions& run,
                                  const ScenarioMeshes& meshes, InspectOptions options,
                                  RunRecord record, ScenarioOutcome& out) {
    AsymmetryOptions asymmetry = take_asymmetry_options(options.analysis, sc.asymmetry.plane);
    asymmetry.validate();
    const Mesh& mesh = meshes.examined;  // the one surface: the reference as derived
    if (auto& roi = asymmetry.plane.registration.roi; roi && roi->needs_mask())
        read_roi_mask(*roi, mesh.vertex_count());
    if (run.observer.stage) run.observer.stage("symmetry plane");
    AsymmetryPlane plane = prepare_asymmetry(mesh, asymmetry);
    out.asymmetry = plane_outcome(sc, meshes, plane.plane);
    if (!plane.plane.plausible) return {};  // a verdict, nothing written (as glint asymmetry)
    const PatientSpace space = reference_space(sc);
    for (auto& in : record.inputs)
        if (in.role == "reference") describe_analysed(sc, mesh, space, in);
    const Orientation orientation = resolve_orientation(space, options.exports.up);
    AsymmetryInspection r = inspect_asymmetry(mesh, std::move(plane), options, std::move(record),
                                              orientation, run.observer);
    const AnalysisResult& result = r.inspection.analysis;
    out.fit_mode = to_string(result.fit.mode);  // none: the mirror is made in place
    out.views = result.sweep.plan.views.size();
    out.output = r.inspection.output;
    const ZoomDecision& z0 = result.decisions.front();
    out.regions = z0.regions.regions.size();
    out.coverage = result.sweep.zooms.front().coverage.fraction;
    out.compared = z0.comparison.fraction;
    out.threshold_deg = z0.normal.value;
    out.warnings = std::move(r.warnings);
    // Kind and side as report.json names them, the side in the reference's frame (the pose
    // undone) so that [expect] can name it whatever the motion.
    const auto& undo = meshes.true_reference_from_examined.linear();
    for (const AsymmetryFinding& f : r.findings.findings)
        out.asymmetry->findings.push_back(
            {.kind = finding_kind(f),
             .side = orientation.name(undo * f.side),
             .center = meshes.true_reference_from_examined * f.centroid});
    const nlohmann::json json = nlohmann::json::parse(r.json);
    for (const auto& f : json["findings"])
        out.asymmetry->texts.push_back(f["text"].get<std::string>());
    if (!out.asymmetry->findings.empty()) out.largest_kind = out.asymmetry->findings[0].kind;
    score_findings(mesh, z0, r.findings, out);
    return z0.regions.regions;
}

}  // namespace glint::detail
