// glint.asymmetry(): left–right asymmetry of one surface (analysis/asymmetry.h), as glint
// asymmetry runs it: the symmetry plane (fitted, or given by plane=), then the surface swept
// against its own mirror image and the regions paired into findings with a side.
#include "analysis/asymmetry.h"
#include "mesh/error.h"
#include "python/bindings.h"
#include "python/interrupt.h"
#include "python/keywords.h"
#include "report/asymmetry_json.h"
#include "report/asymmetry_run.h"
#include "report/inspect.h"
#include "report/orientation.h"
#include "report/run_inputs.h"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace glint::python {

namespace {

/// glint.Asymmetry: one asymmetry() call's results.
struct AsymmetryHandle {
    SymmetryPlaneResult plane;
    AsymmetryFindings findings;
    Orientation orientation;
    std::string unit;  ///< "" = unknown
    std::vector<std::string> warnings;
    std::filesystem::path output;  ///< the folder written (empty when none)
    std::string report;            ///< report.json's text
};

py::dict plane_dict(const SymmetryPlaneResult& r) {
    py::dict d;
    d["normal"] = Eigen::Vector3d(r.plane.normal);
    d["point"] = Eigen::Vector3d(r.plane.point());
    d["offset"] = r.plane.offset;
    d["spec"] = to_string(r.plane);
    d["source"] = r.source;
    d["residual"] = r.rms;
    d["inlier_fraction"] = r.inlier_fraction;
    d["overlap"] = r.overlap;
    d["converged"] = r.converged;
    d["plausible"] = r.plausible;
    d["verdict"] = r.verdict;
    return d;
}

py::list findings_list(const AsymmetryHandle& a) {
    py::list out;
    for (const AsymmetryFinding& f : a.findings.findings) {
        const std::string side = a.orientation.name(f.side);
        const std::string other = a.orientation.name(-f.side);
        py::dict d;
        d["side"] = side;
        d["kind"] = finding_kind(f);
        d["depth"] = f.depth;
        d["area"] = f.area;
        d["volume"] = f.volume;
        d["sentence"] = describe(f, side + " side", other + " side", a.unit);
        d["side_direction"] = Eigen::Vector3d(f.side);
        d["centroid"] = Eigen::Vector3d(f.centroid);
        d["side_chosen_by"] = side_chosen_by(f);
        d["region"] = f.region;
        d["mirror_region"] = f.mirror_region;
        d["at_mirror_image"] = f.at_mirror_image;
        out.append(d);
    }
    return out;
}

// The input as report.json records it (as analyse() does), with the space its file states.
RunInput reference_input(const MeshHandle& h) {
    RunInput in;
    in.record = {"reference", {}, "", h.mesh.vertex_count(), h.mesh.triangle_count()};
    if (h.report) {
        in.record.path = h.report->path;
        for (const auto& w : h.report->warnings) in.warnings.push_back(h.source + ": " + w);
    } else {
        in.record.description = h.source;
    }
    return in;
}

// The CLI's message when no plane is plausible, with the keyword that runs it anyway.
[[noreturn]] void no_plane(const std::string& source, const SymmetryPlaneResult& r) {
    throw Error("asymmetry: \"" + source + "\": " + r.verdict +
                "; no asymmetry is reported and nothing was written (the best plane found, "
                "given by hand, runs anyway: plane='" +
                to_string(r.plane) + "')");
}

// None, or the text of a str keyword. pybind11's own refusal of a wrong type (a std::optional
// parameter) is a message of several lines listing the signature; this one is one line.
std::optional<std::string> optional_text(const py::object& value, const char* keyword) {
    if (value.is_none()) return std::nullopt;
    if (!py::isinstance<py::str>(value))
        throw py::type_error(std::string("asymmetry(): ") + keyword +
                             " must be a str or None, not " +
                             py::cast<std::string>(py::str(value.get_type().attr("__name__"))));
    return py::cast<std::string>(value);
}

AsymmetryHandle run_asymmetry(const MeshLike& mesh, const py::object& plane_value,
                              const py::object& fit_roi_value, const py::object& output_value,
                              const py::kwargs& kwargs) {
    const CallScope call;  // a cancel while the input loads stops the whole call
    const std::optional<std::filesystem::path> output =
        path_argument(output_value, "asymmetry", "output");
    const std::optional<std::string> plane = optional_text(plane_value, "plane");
    const std::optional<std::string> fit_roi = optional_text(fit_roi_value, "fit_roi");
    py::kwargs all = kwargs;
    if (fit_roi) all["fit_roi"] = *fit_roi;
    Keywords k;
    apply_keywords(k, all, kAllKeywords, "asymmetry");
    AsymmetryOptions options = take_asymmetry_options(
        k.analysis, plane ? std::optional(parse_plane_spec(*plane)) : std::nullopt);
    InspectOptions inspect_options{k.analysis, k.exports};
    if (output) inspect_options.exports.output = *output;
    inspect_options.exports.replace_existing = k.force;
    inspect_options.validate();  // before any load, as glint asymmetry does
    options.validate();
    const auto h = mesh_argument(mesh, k.surface, "mesh");
    if (auto& roi = options.plane.registration.roi; roi && roi->needs_mask())
        read_roi_mask(*roi, h->mesh.vertex_count());
    const PatientSpace space = h->report ? space_stated_in(h->report->path) : PatientSpace{};
    AsymmetryHandle a{.orientation = resolve_orientation(space, k.exports.up)};
    RunRecord record{.command_line = "python: glint.asymmetry(...)"};
    record.add(reference_input(*h));
    run_interruptible([&] {
        AsymmetryPlane p = prepare_asymmetry(h->mesh, options);
        a.plane = p.plane;
        if (p.mirror.triangles.empty()) return;
        AsymmetryInspection i =
            inspect_asymmetry(h->mesh, std::move(p), inspect_options, record, a.orientation);
        a.findings = std::move(i.findings);
        a.unit = i.inspection.analysis.unit;
        a.output = i.inspection.output;
        a.report = std::move(i.inspection.report_json);
        a.warnings = std::move(i.warnings);
    });
    if (!a.plane.plausible) no_plane(h->source, a.plane);
    warn(a.warnings);
    return a;
}

void bind_asymmetry_class(py::module_& m) {
    py::class_<AsymmetryHandle>(m, "Asymmetry", "The results of glint.asymmetry().")
        .def_property_readonly(
            "plane", [](const AsymmetryHandle& a) { return plane_dict(a.plane); },
            "the symmetry plane as a dict: normal, point (numpy, mesh units), offset, spec (the "
            "plane= text that gives it back), source ('given' or the hypothesis kept), residual "
            "(RMS of the mirror fit, mesh units), inlier_fraction, overlap, converged, "
            "plausible, verdict (one sentence with the numbers)")
        .def_property_readonly(
            "findings", [](const AsymmetryHandle& a) { return findings_list(a); },
            "one dict per finding: side (where it is reported: 'right', … in a patient space, "
            "else '+x', …), kind ('less', 'more' than the mirrored other side, or 'no mirrored "
            "surface'), depth (peak, mesh units; NaN without a mirror), area, volume (mesh "
            "units², ³; negative = less), sentence (as glint asymmetry prints it), "
            "side_direction, centroid, side_chosen_by, region, mirror_region, at_mirror_image "
            "(True: a lone region shown at its mirror image; `region` lies on the other side)")
        .def_property_readonly(
            "field",
            [](const AsymmetryHandle& a) {
                const auto& f = a.findings.field;
                return py::array_t<float>(static_cast<py::ssize_t>(f.size()), f.data());
            },
            "per vertex (float32): this side minus the mirrored other side along the outward "
            "normal, mesh units (negative: less)")
        .def_property_readonly(
            "symmetry_floor",
            [](const AsymmetryHandle& a) {
                const SymmetryFloor& f = a.findings.floor;
                auto stated = [](double v) -> py::object {
                    return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
                };
                return py::dict(py::arg("rms") = f.rms, py::arg("p95") = f.p95,
                                py::arg("max") = f.max,
                                py::arg("min_detectable_depth") = stated(f.min_depth),
                                py::arg("min_detectable_area") = stated(f.min_area));
            },
            "|field| outside the findings: rms, p95, max (mesh units); the smallest one-sided "
            "change the decision can tell from it: min_detectable_depth (mesh units) over "
            "min_detectable_area (units²), None when not stated")
        .def_property_readonly("caveat", [](const AsymmetryHandle&) { return kOneScanCaveat; })
        .def_property_readonly("unit",
                               [](const AsymmetryHandle& a) -> py::object {
                                   if (a.unit.empty()) return py::none();
                                   return py::str(a.unit);
                               })
        .def_property_readonly("warnings", [](const AsymmetryHandle& a) { return a.warnings; })
        .def_property_readonly(
            "report",
            [](const AsymmetryHandle& a) {
                return py::module_::import("json").attr("loads")(a.report);
            },
            "report.json as a dict")
        .def_property_readonly(
            "output",
            [](const AsymmetryHandle& a) -> py::object {
                if (a.output.empty()) return py::none();
                return py::cast(a.output);
            },
            "the folder written, or None")
        .def("__repr__", [](const AsymmetryHandle& a) {
            return "<glint.Asymmetry " + std::to_string(a.findings.findings.size()) +
                   " finding(s), plane " + to_string(a.plane.plane) + ">";
        });
}

}  // namespace

void bind_asymmetry(py::module_& m) {
    bind_asymmetry_class(m);
    // note: the docstring starts with the text signature ("name(...)\n--\n\n"), which
    // inspect.signature() reads; pybind11's own would come first and hide it.
    py::options options;
    options.disable_function_signatures();
    m.def("asymmetry", &run_asymmetry, py::arg("mesh"), py::kw_only(),
          py::arg("plane") = py::none(), py::arg("fit_roi") = py::none(),
          py::arg("output") = py::none(),
          ("asymmetry(mesh, *, plane=None, fit_roi=None, output=None, **keywords)\n--\n\n"
           "Left-right asymmetry of one surface (as glint asymmetry): fits its symmetry plane "
           "(or checks plane=), compares each side with the mirror of the other and pairs the "
           "regions into findings, each reported on one side.\n"
           "mesh: glint.Mesh, a path, (vertices, triangles) arrays or a mesh of Open3D, trimesh "
           "or PyVista. plane: 'x=C' (or y=, z=), 'point=x,y,z;normal=x,y,z' or "
           "'landmarks=x,y,z/x,y,z/x,y,z'. fit_roi: fit the plane on this region only "
           "(sphere:x,y,z,r, box:…, mask:FILE). output: also write the folder glint asymmetry "
           "writes.\n"
           "Returns glint.Asymmetry. Raises glint.Error when no plane is plausible (the message "
           "gives the best plane found as a plane= value), glint.InputError for a bad keyword "
           "value or plane text. Ctrl-C stops it (KeyboardInterrupt). Warnings are issued as "
           "glint.GlintWarning and kept in Asymmetry.warnings. " +
           std::string(kOneScanCaveat) +
           ".\n\nKeywords (name: type = default [unit] — meaning; accepted values):\n" +
           keyword_docs(kAllKeywords))
              .c_str());
}

}  // namespace glint::python
