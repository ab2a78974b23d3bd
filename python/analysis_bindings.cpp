// glint.register() and glint.analyse(): the fit with its evidence, the atlas as numpy arrays,
// regions and the report as Python objects. The report is report.json's text
// (report/report.h), parsed by Python's json module; nothing here re-computes it.
#include "python/bindings.h"

#include "analysis/analysis.h"
#include "analysis/fit.h"
#include "analysis/units.h"
#include "mesh/atomic_file.h"
#include "mesh/geometry.h"
#include "python/interrupt.h"
#include "python/keywords.h"
#include "report/inspect.h"
#include "report/report.h"
#include "report/run_inputs.h"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>

namespace py = pybind11;

namespace glint::python {

namespace {

/// glint.Fit: examined → reference, with the registration's evidence.
struct FitHandle {
    FitOutcome outcome;
    std::string unit;  ///< of the translation and the RMS ("" = unknown)
};

/// glint.Analysis: one analyse() call's results.
struct AnalysisHandle {
    AnalysisResult result;
    std::filesystem::path output;       ///< the folder written (empty when none)
    std::shared_ptr<MeshHandle> atlas;  ///< the reference with the atlas fields (make_atlas_mesh)
    std::string report;                 ///< report.json's text
    std::string regions_csv;            ///< regions.csv's text
    FitHandle fit;
};

py::object json_loads(const std::string& text) {
    return py::module_::import("json").attr("loads")(text);
}

py::object optional_string(const std::string& s) {
    return s.empty() ? py::object(py::none()) : py::object(py::str(s));
}

// The registration's evidence, or None when the fit came from a file or was the identity.
template <class Get>
py::object evidence(const FitHandle& f, Get get) {
    if (!f.outcome.registration) return py::none();
    return py::cast(get(*f.outcome.registration));
}

FitMode fit_mode(bool do_register, const std::optional<std::filesystem::path>& fit_file) {
    if (fit_file) return FitMode::File;
    return do_register ? FitMode::Register : FitMode::Identity;
}

FitHandle register_pair(const MeshLike& reference, const MeshLike& examined,
                        const py::object& output_value, const py::kwargs& kwargs) {
    const CallScope call;  // a cancel while the inputs load stops the whole call
    const std::optional<std::filesystem::path> output =
        path_argument(output_value, "register", "output");
    Keywords k;
    apply_keywords(k, kwargs, kSurfaceKeywords | kFitGroup | kUnitGroup, "register");
    FitOptions& fit = k.analysis.fit;
    fit.mode = FitMode::Register;
    fit.validate();
    k.analysis.units.validate();
    const auto ref = mesh_argument(reference, k.surface, "reference");
    const auto exa = mesh_argument(examined, k.surface, "examined");
    std::vector<std::string> unit_warnings;
    FitHandle f = run_interruptible_value([&] {
        // As glint register: sizes checked first, files in two stated units fitted in the
        // reference's.
        const UnitResolution units = resolve_units(ref->mesh, exa->mesh, k.analysis.units);
        unit_warnings = units.warnings;
        Mesh moved = exa->mesh;
        scale_to_analysis_unit(moved, units);
        FitOptions scaled_fit = fit;
        if (scaled_fit.registration.fit_scale)
            scaled_fit.registration.initial_scale *= starting_scale(units);
        FitHandle fitted{fit_examined(ref->mesh, moved, scaled_fit), units.unit};
        if (output) write_file_atomically(*output, fitted.outcome.json);
        return fitted;
    });
    unit_warnings.insert(unit_warnings.end(), f.outcome.warnings.begin(), f.outcome.warnings.end());
    warn(unit_warnings);
    return f;
}

// The input as report.json records it: the file it came from, or what made it.
RunInput run_input(const char* role, const MeshHandle& h) {
    RunInput in;
    in.record = {role, {}, "", h.mesh.vertex_count(), h.mesh.triangle_count()};
    if (h.report) {
        in.record.path = h.report->path;
        for (const auto& w : h.report->warnings) in.warnings.push_back(h.source + ": " + w);
    } else {
        in.record.description = h.source;
    }
    return in;
}

AnalysisHandle analyse_pair(const MeshLike& reference, const MeshLike& examined,
                            const py::object& register_value, const py::object& fit_value,
                            const py::object& output_value, const py::kwargs& kwargs) {
    const CallScope call;  // a cancel while the inputs load stops the whole call
    const bool do_register = bool_argument(register_value, "analyse", "register");
    const std::optional<std::filesystem::path> fit_file =
        path_argument(fit_value, "analyse", "fit");
    const std::optional<std::filesystem::path> output =
        path_argument(output_value, "analyse", "output");
    Keywords k;
    apply_keywords(k, kwargs, kAllKeywords, "analyse");
    InspectOptions options{k.analysis, k.exports};
    options.analysis.fit.mode = fit_mode(do_register, fit_file);
    if (fit_file) options.analysis.fit.fit_file = *fit_file;
    if (output) options.exports.output = *output;
    options.exports.replace_existing = k.force;
    options.exports.keep_atlas = true;
    options.validate();  // before any load, as glint sweep does
    const auto ref = mesh_argument(reference, k.surface, "reference");
    const auto exa = mesh_argument(examined, k.surface, "examined");
    RunRecord record{.command_line = "python: glint.analyse(...)"};
    record.add(run_input("reference", *ref));
    record.add(run_input("examined", *exa));
    if (fit_file) record.add_file("fit", *fit_file);
    AnalysisHandle analysis = run_interruptible_value([&] {
        Inspection inspection = inspect(ref->mesh, exa->mesh, options, record);
        AnalysisHandle a;
        a.result = std::move(inspection.analysis);
        a.output = inspection.output;
        a.atlas = std::make_shared<MeshHandle>();
        a.atlas->mesh = std::move(*inspection.atlas);
        a.atlas->source = "atlas of " + ref->source;
        a.report = std::move(inspection.report_json);
        a.regions_csv = glint::regions_csv(a.result);
        a.fit = FitHandle{a.result.fit, a.result.unit};
        return a;
    });
    warn(analysis.result.warnings);  // they stay in Analysis.warnings and report.json too
    return analysis;
}

void bind_fit(py::module_& m) {
    py::class_<FitHandle>(m, "Fit",
                          "A fit of the examined mesh onto the reference (rigid, or a similarity "
                          "with fit_scale=True), with its evidence.")
        .def_property_readonly(
            "matrix",
            [](const FitHandle& f) {
                return Eigen::Matrix4d(f.outcome.reference_from_examined.matrix());
            },
            "4×4 float64 reference_from_examined (maps examined points, after multiplying them "
            "by `scale`, into the reference frame)")
        .def_property_readonly(
            "scale", [](const FitHandle& f) { return f.outcome.examined_scale; },
            "the examined surface's fitted scale (1.0 unless fit_scale=True or a fit file says "
            "otherwise)")
        .def_property_readonly(
            "scale_uncertainty",
            [](const FitHandle& f) {
                return evidence(f, [](const RegistrationResult& r) { return r.scale_uncertainty; });
            },
            "one standard error of `scale` (jackknife over the surface's octants); None without "
            "a registration")
        .def_property_readonly(
            "scale_trend",
            [](const FitHandle& f) {
                return evidence(f, [](const RegistrationResult& r) { return r.scale_trend; });
            },
            "the relative scale a similarity step would still add at the fitted pose (the "
            "radial trend of the signed distance; -0.01: the examined stands 1 % too large)")
        .def_property_readonly(
            "rotation",
            [](const FitHandle& f) {
                return Eigen::Matrix3d(f.outcome.reference_from_examined.linear());
            },
            "3×3 rotation of reference_from_examined")
        .def_property_readonly(
            "translation",
            [](const FitHandle& f) {
                return Eigen::Vector3d(f.outcome.reference_from_examined.translation());
            },
            "translation of reference_from_examined (mesh units)")
        .def_property_readonly("rotation_deg",
                               [](const FitHandle& f) {
                                   return rotation_angle_deg(f.outcome.reference_from_examined);
                               })
        .def_property_readonly(
            "mode", [](const FitHandle& f) { return to_string(f.outcome.mode); },
            "register, file, identity or truth")
        .def_property_readonly("converged", [](const FitHandle& f) { return f.outcome.converged; })
        .def_property_readonly(
            "rms",
            [](const FitHandle& f) {
                return evidence(f, [](const RegistrationResult& r) { return r.rms; });
            },
            "point-to-plane RMS of the inliers (mesh units); None without a registration")
        .def_property_readonly(
            "inlier_fraction",
            [](const FitHandle& f) {
                return evidence(f, [](const RegistrationResult& r) { return r.inlier_fraction; });
            })
        .def_property_readonly("overlap",
                               [](const FitHandle& f) {
                                   return evidence(
                                       f, [](const RegistrationResult& r) { return r.overlap; });
                               })
        .def_property_readonly("iterations",
                               [](const FitHandle& f) {
                                   return evidence(
                                       f, [](const RegistrationResult& r) { return r.iterations; });
                               })
        .def_property_readonly(
            "termination",
            [](const FitHandle& f) {
                return evidence(f, [](const RegistrationResult& r) { return r.termination; });
            })
        .def_property_readonly("termination_detail",
                               [](const FitHandle& f) {
                                   return evidence(f, [](const RegistrationResult& r) {
                                       return r.termination_detail;
                                   });
                               })
        .def_property_readonly("unit", [](const FitHandle& f) { return optional_string(f.unit); })
        .def_property_readonly("warnings", [](const FitHandle& f) { return f.outcome.warnings; })
        .def(
            "to_dict", [](const FitHandle& f) { return json_loads(f.outcome.json); },
            "the fit as fit.json holds it (evidence, per-iteration log, options)")
        .def(
            "save",
            [](const FitHandle& f, const std::filesystem::path& path) {
                write_file_atomically(path, f.outcome.json);
            },
            py::arg("path"),
            "Writes fit.json (glint sweep --fit and glint.analyse(fit=…) read it).")
        .def("__repr__", [](const FitHandle& f) {
            return "<glint.Fit " + to_string(f.outcome.mode) +
                   (f.outcome.converged ? ", converged" : ", NOT converged") + ", rotation " +
                   std::to_string(rotation_angle_deg(f.outcome.reference_from_examined)) + " deg>";
        });
}

void bind_analysis_class(py::module_& m) {
    py::class_<AnalysisHandle>(m, "Analysis", "The results of glint.analyse().")
        .def_property_readonly(
            "atlas", [](const AnalysisHandle& a) { return a.atlas; },
            "the reference surface (glint.Mesh) coloured by damage, with every atlas field in "
            "atlas.scalars (the scalars of atlas.ply)")
        .def_property_readonly(
            "fields",
            [](const AnalysisHandle& a) -> py::object { return py::cast(a.atlas).attr("scalars"); },
            "per-vertex numpy arrays by name, each named with its unit (docs/outputs.md: the atlas "
            "fields): shape_change_mm (signed distance to the fitted examined surface, negative "
            "= loss, in a hole of the examined surface the depth gone; _units when the unit is "
            "unknown), shape_tolerance_mm, and per zoom k: "
            "seen_z<k> (1 seen, 0 unseen), angle_mean_deg_z<k>, angle_max_deg_z<k>, "
            "missing_fraction_z<k> (0 where unseen), pixels_z<k>, region_id_z<k>")
        .def_property_readonly(
            "report", [](const AnalysisHandle& a) { return json_loads(a.report); },
            "report.json as a dict")
        .def_property_readonly(
            "regions",
            [](const AnalysisHandle& a) {
                py::list regions;
                const py::object report = json_loads(a.report);
                for (const py::handle zoom : report["zooms"])
                    for (const py::handle region : zoom["regions"]) {
                        py::dict r = py::reinterpret_borrow<py::dict>(region);
                        r["zoom"] = zoom["zoom"];
                        regions.append(r);
                    }
                return regions;
            },
            "every region of every zoom as a dict (report.json's, with its zoom)")
        .def_property_readonly(
            "regions_csv", [](const AnalysisHandle& a) { return a.regions_csv; },
            "regions.csv's text")
        .def_property_readonly("fit", [](const AnalysisHandle& a) { return a.fit; })
        .def_property_readonly(
            "unit", [](const AnalysisHandle& a) { return optional_string(a.result.unit); })
        .def_property_readonly("warnings",
                               [](const AnalysisHandle& a) { return a.result.warnings; })
        .def_property_readonly(
            "output",
            [](const AnalysisHandle& a) -> py::object {
                if (a.output.empty()) return py::none();
                return py::cast(a.output);
            },
            "the folder written, or None")
        .def("__repr__", [](const AnalysisHandle& a) {
            std::size_t regions = 0;
            for (const auto& d : a.result.decisions) regions += d.regions.regions.size();
            return "<glint.Analysis " + std::to_string(a.result.decisions.size()) + " zoom(s), " +
                   std::to_string(regions) + " region(s)>";
        });
}

}  // namespace

void bind_analysis(py::module_& m) {
    bind_fit(m);
    bind_analysis_class(m);
    // The three functions take their option keywords as **kwargs (the registry checks them), so
    // pybind11's signature would say "**kwargs". Their docstrings begin with the signature in
    // CPython's text-signature form instead ("name(...)\n--\n\n"): help() and
    // inspect.signature() then list every keyword with its default.
    py::options signatures;
    signatures.disable_function_signatures();
    m.def(
        "register", &register_pair, py::arg("reference"), py::arg("examined"), py::kw_only(),
        py::arg("output") = py::none(),
        ("register(reference, examined, *, output=None, " +
         keyword_signature(kSurfaceKeywords | kFitGroup | kUnitGroup) +
         ")\n--\n\n"
         "Fits the examined surface onto the reference (robust ICP, as glint register).\n\n"
         "reference, examined: " GLINT_MESH_LIKE_TYPES "\noutput: also write fit.json there.\n"
         "Warnings (an assumed unit, …) are issued as glint.GlintWarning and kept in "
         "fit.warnings.\n"
         "Returns glint.Fit (a fit that did not converge is a result: fit.converged is False).\n\n"
         "Keywords (name: type = default [unit] — meaning; accepted values):\n" +
         keyword_docs(kSurfaceKeywords | kFitGroup | kUnitGroup))
            .c_str());
    m.def(
        "analyse", &analyse_pair, py::arg("reference"), py::arg("examined"), py::kw_only(),
        py::arg("register") = true, py::arg("fit") = py::none(), py::arg("output") = py::none(),
        ("analyse(reference, examined, *, register=True, fit=None, output=None, " +
         keyword_signature(kAllKeywords) +
         ")\n--\n\n"
         "The whole analysis (as glint sweep): fit (register=True, or fit='fit.json', or "
         "register=False for meshes already aligned), signed distance, sweep, decision and, with "
         "output=, the folder glint sweep writes.\nreference, examined: " GLINT_MESH_LIKE_TYPES "\n"
         "Returns glint.Analysis. Ctrl-C stops it (KeyboardInterrupt; nothing half-written). "
         "Warnings are issued as glint.GlintWarning and kept in Analysis.warnings.\n\n"
         "Keywords (name: type = default [unit] — meaning; accepted values):\n" +
         keyword_docs(kAllKeywords))
            .c_str());
    m.def(
        "options",
        [](const py::object& register_value, const py::object& fit_value,
           const py::kwargs& kwargs) {
            const bool do_register = bool_argument(register_value, "options", "register");
            const std::optional<std::filesystem::path> fit_file =
                path_argument(fit_value, "options", "fit");
            Keywords k;
            apply_keywords(k, kwargs, kAllKeywords & ~kSurfaceKeywords & ~kForceKeyword, "options");
            k.analysis.fit.mode = fit_mode(do_register, fit_file);
            if (fit_file) k.analysis.fit.fit_file = *fit_file;
            k.analysis.validate();
            k.exports.validate();
            return json_loads(options_json(k));
        },
        py::kw_only(), py::arg("register") = true, py::arg("fit") = py::none(),
        ("options(*, register=True, fit=None, " +
         keyword_signature(kAllKeywords & ~kSurfaceKeywords & ~kForceKeyword) +
         ")\n--\n\n"
         "The options analyse() would run with, resolved from these keywords, as a dict laid out "
         "as a scenario file's sections (glint sweep --print-options prints the same).\n\n"
         "Keywords:\n" +
         keyword_docs(kAllKeywords & ~kSurfaceKeywords & ~kForceKeyword))
            .c_str());
}

}  // namespace glint::python
