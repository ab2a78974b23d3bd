#include "report/asymmetry_json.h"

#include "mesh/json_text.h"
#include "mesh/units.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {
namespace {

double axis_angle_deg(const Vec3d& n, int axis) {
    return std::acos(std::min(1.0, std::abs(n[axis]))) * 180.0 / std::numbers::pi;
}

nlohmann::json plane_object(const SymmetryPlaneResult& r, const std::string& unit) {
    const SymmetryPlane& p = r.plane;
    nlohmann::json hypotheses = nlohmann::json::array();
    for (const auto& h : r.hypotheses)
        hypotheses.push_back(
            {{"name", h.name},
             {"normal", {h.plane.normal.x(), h.plane.normal.y(), h.plane.normal.z()}},
             {"offset", h.plane.offset},
             {"rms", h.rms},
             {"overlap", h.overlap},
             {"converged", h.converged}});
    return {
        {"normal", {p.normal.x(), p.normal.y(), p.normal.z()}},
        {"point", {p.point().x(), p.point().y(), p.point().z()}},
        {"offset", p.offset},
        {"angle_to_axes_deg",
         {axis_angle_deg(p.normal, 0), axis_angle_deg(p.normal, 1), axis_angle_deg(p.normal, 2)}},
        {"source", r.source},
        {"residual", r.rms},
        {"residual_text", with_unit(r.rms, unit)},
        {"inlier_fraction", r.inlier_fraction},
        {"overlap", r.overlap},
        {"mirror_share", r.mirror_share},
        {"mirror_share_other_face", r.mirror_share_opposite},
        {"converged", r.converged},
        {"plausible", r.plausible},
        {"verdict", r.verdict},
        {"hypotheses", hypotheses}};
}

// report.json's "asymmetry": the plane, the floor, the findings side by side.
nlohmann::json asymmetry_object(const SymmetryPlaneResult& plane, const AsymmetryFindings& f,
                                const Orientation& o, const std::string& unit) {
    nlohmann::json findings = nlohmann::json::array();
    for (const auto& x : f.findings) {
        const std::string side = o.name(x.side), other = o.name(-x.side);
        findings.push_back({{"side", side},
                            {"text", describe(x, side + " side", other + " side", unit)},
                            {"kind", finding_kind(x)},
                            {"less", x.depth < 0},
                            {"mirror_missing", x.mirror_missing},
                            {"side_chosen_by", side_chosen_by(x)},
                            {"roughness", x.roughness},
                            {"mirror_roughness", x.mirror_roughness},
                            {"depth", x.depth},
                            {"area", x.area},
                            {"volume", x.volume},
                            {"centroid", {x.centroid.x(), x.centroid.y(), x.centroid.z()}},
                            {"region", x.region},
                            {"mirror_region", x.mirror_region},
                            {"at_mirror_image", x.at_mirror_image}});
    }
    nlohmann::json plane_json = plane_object(plane, unit);
    // The plane's numbers are in the surface's coordinates: a volume's physical frame as its
    // header gives it (report/orientation.h), or the mesh file's; its normal named as the sides.
    plane_json["frame"] = o.space == PatientSpace::Unknown ? "mesh coordinates (no patient space)"
                                                           : to_string(o.space);
    plane_json["normal_towards"] = o.name(plane.plane.normal);
    // The floor's numbers and, once, their words: the terminal and report.html print these.
    nlohmann::json floor = {{"rms", f.floor.rms},
                            {"p95", f.floor.p95},
                            {"max", f.floor.max},
                            {"min_detectable_depth", f.floor.min_depth},
                            {"min_detectable_area", f.floor.min_area},
                            {"unit", unit},
                            {"spread_text", "|asymmetry| RMS " + with_unit(f.floor.rms, unit) +
                                                ", 95 % below " + with_unit(f.floor.p95, unit)}};
    // note: not stated (null) when no decision ran, e.g. nothing could be compared
    if (std::isfinite(f.floor.min_depth) && std::isfinite(f.floor.min_area))
        floor["min_detectable_text"] = with_unit(f.floor.min_depth, unit) + " deep over " +
                                       with_unit(f.floor.min_area, unit, 2, "%.3g");
    return {{"plane", std::move(plane_json)},
            {"symmetry_floor", std::move(floor)},
            {"findings", findings},
            {"caveat", std::string(kOneScanCaveat)},
            {"field",
             "asymmetry: this side minus the mirrored other side along the outward "
             "normal (negative: less)"},
            {"regions_note",
             "regions, regions.csv and the pictures give this side against the mirrored other "
             "side, as the findings do: a dent (blue) is where this side has less"}};
}

}  // namespace

MirrorPictures mirror_pictures(const SymmetryPlaneResult& plane) {
    return {.normal = plane.plane.normal, .offset = plane.plane.offset, .residual = plane.rms};
}

std::string side_chosen_by(const AsymmetryFinding& finding) {
    return finding.side_by_shape ? "the side whose surface bends less evenly there"
                                 : "the side with less";
}

std::string finding_kind(const AsymmetryFinding& finding) {
    if (finding.mirror_missing) return "no mirrored surface";
    return finding.depth < 0 ? "less" : "more";
}

std::string symmetry_plane_json(const SymmetryPlaneResult& plane, const std::string& unit) {
    return json_text(plane_object(plane, unit));
}

std::string asymmetry_json(const SymmetryPlaneResult& plane, const AsymmetryFindings& findings,
                           const Orientation& orientation, const std::string& unit) {
    return json_text(asymmetry_object(plane, findings, orientation, unit));
}

}  // namespace glint
