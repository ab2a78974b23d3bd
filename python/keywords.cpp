#include "python/keywords.h"

#include "mesh/error.h"
#include "mesh/roi.h"
#include "registration/icp.h"
#include "render/context.h"
#include "scanner/metric.h"
#include "scanner/plan.h"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <filesystem>
#include <functional>
#include <vector>

namespace py = pybind11;

namespace glint::python {

namespace {

struct Keyword {
    const char* name;
    KeywordGroup group;
    const char* expected;  ///< for the error on a wrong type
    std::function<void(Keywords&, py::handle)> apply;
};

template <class T>
T as(py::handle value) {
    return py::cast<T>(value);
}

// note: pybind11 converts anything with __bool__ to bool ("no" would be True); a flag takes
// True or False only.
template <>
bool as<bool>(py::handle value) {
    if (!PyBool_Check(value.ptr())) throw py::cast_error("not a bool");
    return value.ptr() == Py_True;
}

const std::vector<Keyword>& keywords() {
    static const std::vector<Keyword> table = {
        // Surfaces of volumes (volume/surface.h).
        {"iso", kSurfaceKeywords, "a number",
         [](Keywords& k, py::handle v) { k.surface.iso = as<double>(v); }},
        {"surface_roi", kSurfaceKeywords, "a string (sphere:… or box:…)",
         [](Keywords& k, py::handle v) { k.surface.roi = parse_roi(as<std::string>(v)); }},
        {"largest", kSurfaceKeywords, "a bool",
         [](Keywords& k, py::handle v) { k.surface.largest = as<bool>(v); }},
        {"seed", kSurfaceKeywords, "three numbers (mm)",
         [](Keywords& k, py::handle v) {
             const auto p = as<std::array<double, 3>>(v);
             k.surface.seed = Vec3d(p[0], p[1], p[2]);
         }},
        {"smooth", kSurfaceKeywords, "an integer",
         [](Keywords& k, py::handle v) { k.surface.smooth_iterations = as<int>(v); }},
        {"passband", kSurfaceKeywords, "a number",
         [](Keywords& k, py::handle v) { k.surface.passband = as<double>(v); }},
        {"edge", kSurfaceKeywords, "a number (mm)",
         [](Keywords& k, py::handle v) { k.surface.edge_mm = as<double>(v); }},
        {"tolerance", kSurfaceKeywords, "a number (mm)",
         [](Keywords& k, py::handle v) { k.surface.tolerance_mm = as<double>(v); }},
        // Registration (scanner/fit.h, registration/icp.h).
        {"loss", kFitKeywords, "a string",
         [](Keywords& k, py::handle v) {
             k.analysis.fit.registration.loss = parse_loss(as<std::string>(v));
         }},
        {"fit_roi", kFitKeywords, "a string (sphere:…, box:… or mask:FILE)",
         [](Keywords& k, py::handle v) {
             k.analysis.fit.registration.roi = parse_roi(as<std::string>(v));
         }},
        {"landmarks", kFitKeywords, "a path",
         [](Keywords& k, py::handle v) {
             k.analysis.fit.landmarks_file = as<std::filesystem::path>(v);
         }},
        {"init", kFitKeywords, "a path",
         [](Keywords& k, py::handle v) {
             k.analysis.fit.init_file = as<std::filesystem::path>(v);
         }},
        {"samples", kFitKeywords, "an integer",
         [](Keywords& k, py::handle v) { k.analysis.fit.registration.samples = as<int>(v); }},
        {"max_iterations", kFitKeywords, "an integer",
         [](Keywords& k, py::handle v) {
             k.analysis.fit.registration.max_iterations = as<int>(v);
         }},
        {"symmetric", kFitKeywords, "a bool",
         [](Keywords& k, py::handle v) { k.analysis.fit.registration.symmetric = as<bool>(v); }},
        {"coarse", kFitKeywords, "a bool",
         [](Keywords& k, py::handle v) { k.analysis.fit.registration.coarse = as<bool>(v); }},
        // Units (scanner/units.h).
        {"unit", kUnitKeywords, "a string",
         [](Keywords& k, py::handle v) { k.analysis.units.unit = as<std::string>(v); }},
        {"allow_scale_mismatch", kUnitKeywords, "a bool",
         [](Keywords& k, py::handle v) { k.analysis.units.allow_scale_mismatch = as<bool>(v); }},
        // The sweep (scanner/sweep.h, scanner/plan.h).
        {"plan", kSweepKeywords, "a string (rotary or sphere:N)",
         [](Keywords& k, py::handle v) {
             parse_plan_kind(as<std::string>(v), k.analysis.sweep.plan);
         }},
        {"azimuth_step", kSweepKeywords, "a number (degrees)",
         [](Keywords& k, py::handle v) { k.analysis.sweep.plan.azimuth_step_deg = as<double>(v); }},
        {"elevations", kSweepKeywords, "a sequence of numbers (degrees)",
         [](Keywords& k, py::handle v) {
             k.analysis.sweep.plan.elevations_deg = as<std::vector<double>>(v);
         }},
        {"zoom", kSweepKeywords, "a sequence of footprints (mesh units per pixel)",
         [](Keywords& k, py::handle v) {
             k.analysis.sweep.plan.footprints = as<std::vector<double>>(v);
         }},
        {"roi", kSweepKeywords, "a string (sphere:…, box:… or mask:FILE)",
         [](Keywords& k, py::handle v) {
             k.analysis.sweep.plan.roi = parse_roi(as<std::string>(v));
         }},
        {"size", kSweepKeywords, "an integer (pixels)",
         [](Keywords& k, py::handle v) { k.analysis.sweep.plan.size = as<int>(v); }},
        {"supersample", kSweepKeywords, "an integer",
         [](Keywords& k, py::handle v) { k.analysis.sweep.render.supersample = as<int>(v); }},
        {"metric", kSweepKeywords, "a string",
         [](Keywords& k, py::handle v) {
             k.analysis.sweep.metric = parse_metric(as<std::string>(v));
         }},
        {"backend", kSweepKeywords, "a string (auto, vulkan, embree)",
         [](Keywords& k, py::handle v) {
             k.analysis.sweep.render.backend = parse_backend(as<std::string>(v));
         }},
        {"device", kSweepKeywords, "a string",
         [](Keywords& k, py::handle v) { k.analysis.sweep.render.device = as<std::string>(v); }},
        {"accumulate", kSweepKeywords, "a string (auto, gpu, host)",
         [](Keywords& k, py::handle v) {
             k.analysis.sweep.accumulate = parse_accumulation(as<std::string>(v));
         }},
        {"max_incidence", kSweepKeywords, "a number (degrees)",
         [](Keywords& k, py::handle v) { k.analysis.sweep.max_incidence_deg = as<double>(v); }},
        // The decision (scanner/decision.h).
        {"rule", kDecisionKeywords, "a string (fused or normal)",
         [](Keywords& k, py::handle v) {
             k.analysis.decision.rule = parse_decision_rule(as<std::string>(v));
         }},
        {"threshold_deg", kDecisionKeywords, "a number",
         [](Keywords& k, py::handle v) { k.analysis.decision.threshold = as<double>(v); }},
        {"noise_k", kDecisionKeywords, "a number",
         [](Keywords& k, py::handle v) { k.analysis.decision.noise_k = as<double>(v); }},
        {"min_threshold_deg", kDecisionKeywords, "a number",
         [](Keywords& k, py::handle v) { k.analysis.decision.min_threshold = as<double>(v); }},
        {"shape_threshold", kDecisionKeywords, "a number (mesh units)",
         [](Keywords& k, py::handle v) { k.analysis.decision.shape_threshold = as<double>(v); }},
        {"min_region_vertices", kDecisionKeywords, "a non-negative integer",
         [](Keywords& k, py::handle v) {
             k.analysis.decision.min_region_vertices = as<std::size_t>(v);
         }},
        // Exports (scanner/analysis.h).
        {"views", kExportKeywords, "a bool",
         [](Keywords& k, py::handle v) { k.analysis.exports.write_views = as<bool>(v); }},
        {"exr", kExportKeywords, "a bool",
         [](Keywords& k, py::handle v) { k.analysis.exports.write_exr = as<bool>(v); }},
        {"force", kExportKeywords, "a bool",
         [](Keywords& k, py::handle v) { k.analysis.exports.replace_existing = as<bool>(v); }},
    };
    return table;
}

}  // namespace

std::string keyword_names(unsigned groups) {
    std::string names;
    for (const Keyword& k : keywords())
        if ((groups & k.group) != 0) names += (names.empty() ? "" : ", ") + std::string(k.name);
    return names;
}

void apply_keywords(Keywords& into, const py::kwargs& kwargs, unsigned groups,
                    const std::string& function) {
    for (const auto& [key, value] : kwargs) {
        const auto name = py::cast<std::string>(key);
        const Keyword* found = nullptr;
        for (const Keyword& k : keywords())
            if ((groups & k.group) != 0 && name == k.name) found = &k;
        if (found == nullptr)
            throw py::type_error(function + "() got an unexpected keyword argument '" + name +
                                 "'; it takes: " + keyword_names(groups));
        if (value.is_none()) continue;  // None: the library's default
        try {
            found->apply(into, value);
        } catch (const py::cast_error&) {
            throw InputError(function + ": " + name + " = " +
                             py::cast<std::string>(py::repr(value)) + ": expected " +
                             found->expected);
        } catch (const InputError& e) {
            throw InputError(function + ": " + name + ": " + e.what());
        }
    }
}

}  // namespace glint::python
