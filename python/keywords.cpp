#include "python/keywords.h"

#include "mesh/error.h"
#include "mesh/roi.h"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <regex>
#include <vector>

namespace py = pybind11;

namespace glint::python {

namespace {

/// A surface keyword (volume/surface.h): not an analysis option, so written here.
struct SurfaceKeyword {
    const char* name;
    const char* expected;  ///< for the error on a wrong type
    const char* help;
    std::function<void(SurfaceOptions&, py::handle)> apply;
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

// A whole number: a Python int (not a bool), or a float with no fraction (2.0), never truncated.
int as_int(py::handle value) {
    if (PyBool_Check(value.ptr())) throw py::cast_error("a bool is not an integer");
    if (PyFloat_Check(value.ptr())) {
        const double d = value.cast<double>();
        if (!(std::isfinite(d) && d == std::floor(d) && std::fabs(d) < 2e9))
            throw py::cast_error("not a whole number");
        return static_cast<int>(d);
    }
    return py::cast<int>(value);
}

const std::vector<SurfaceKeyword>& surface_keywords() {
    static const std::vector<SurfaceKeyword> table = {
        {"iso", "a number", "Volumes: iso value of the surface, in the volume's units",
         [](SurfaceOptions& s, py::handle v) { s.iso = as<double>(v); }},
        {"surface_roi", "a string (sphere:… or box:…)",
         "Volumes: extract only inside this region (physical mm)",
         [](SurfaceOptions& s, py::handle v) { s.roi = parse_roi(as<std::string>(v)); }},
        {"largest", "a bool", "Volumes: keep only the largest connected surface",
         [](SurfaceOptions& s, py::handle v) { s.largest = as<bool>(v); }},
        {"seed", "three numbers (mm)", "Volumes: keep only the connected surface nearest x, y, z",
         [](SurfaceOptions& s, py::handle v) {
             const auto p = as<std::array<double, 3>>(v);
             s.seed = Vec3d(p[0], p[1], p[2]);
         }},
        {"smooth", "an integer", "Volumes: windowed-sinc smoothing iterations (0: none)",
         [](SurfaceOptions& s, py::handle v) { s.smooth_iterations = as_int(v); }},
        {"passband", "a number", "Volumes: windowed-sinc pass band (0, 2), lower smooths more",
         [](SurfaceOptions& s, py::handle v) { s.passband = as<double>(v); }},
        {"edge", "a number (mm)", "Volumes: decimate to this mean edge length (0: keep all)",
         [](SurfaceOptions& s, py::handle v) { s.edge_mm = as<double>(v); }},
        {"tolerance", "a number (mm)", "Volumes: decimation moves the surface at most this far",
         [](SurfaceOptions& s, py::handle v) { s.tolerance_mm = as<double>(v); }},
    };
    return table;
}

// A Python value as an option's kind. bool only from True/False, integers not from bools,
// paths from os.PathLike, lists from any sequence of numbers. \throw py::cast_error.
OptionValue option_value(const OptionInfo& info, py::handle v) {
    switch (info.kind) {
        case OptionKind::Flag: return as<bool>(v);
        case OptionKind::Integer:
            if (PyBool_Check(v.ptr())) throw py::cast_error("a bool is not an integer");
            if (PyFloat_Check(v.ptr())) return v.cast<double>();  // 2.0 passes, 2.5 is refused
            return py::cast<std::int64_t>(v);
        case OptionKind::Number:
        case OptionKind::OptionalNumber:
            if (PyBool_Check(v.ptr())) throw py::cast_error("a bool is not a number");
            return py::cast<double>(v);
        case OptionKind::Numbers:
            if (py::isinstance<py::str>(v)) throw py::cast_error("a string is not numbers");
            if (PyFloat_Check(v.ptr()) || PyLong_Check(v.ptr()))
                return std::vector<double>{py::cast<double>(v)};
            return py::cast<std::vector<double>>(v);
        case OptionKind::Path: return py::cast<std::filesystem::path>(v).string();
        case OptionKind::Choice:
        case OptionKind::Text:
        case OptionKind::Region: return py::cast<std::string>(v);
    }
    throw py::cast_error("unknown kind");
}

const char* kind_name(OptionKind k) {
    switch (k) {
        case OptionKind::Flag: return "bool";
        case OptionKind::Integer: return "int";
        case OptionKind::Number: return "float";
        case OptionKind::OptionalNumber: return "float | None";
        case OptionKind::Numbers: return "sequence of float";
        case OptionKind::Choice: return "str";
        case OptionKind::Text: return "str";
        case OptionKind::Region: return "str (region)";
        case OptionKind::Path: return "path";
    }
    return "?";
}

// A default as Python writes it: True, 'cauchy', [-60, -30, 0], None (the registry's text
// is the command line's: true, cauchy, -60,-30,0, "").
std::string python_default(OptionKind kind, const std::string& text) {
    if (text.empty()) return "None";
    switch (kind) {
        case OptionKind::Flag: return text == "true" ? "True" : "False";
        case OptionKind::Numbers: {
            std::string list = "[";
            for (char c : text) list += c == ',' ? std::string(", ") : std::string(1, c);
            return list + "]";
        }
        case OptionKind::Choice:
        case OptionKind::Text:
        case OptionKind::Region:
        case OptionKind::Path: return "'" + text + "'";
        default: return text;
    }
}

// Calls `visit(info, default text)` for each registry keyword of `groups`, in table order.
template <class Visit>
void for_each_registry_keyword(unsigned groups, Visit visit) {
    const AnalysisOptions analysis;
    const ExportOptions exports;
    for (const auto& f : analysis_option_table())
        if ((f.info.group & groups) != 0) visit(f.info, option_text(f.info, f.get(analysis)));
    for (const auto& f : export_option_table())
        if ((f.info.group & groups) != 0) visit(f.info, option_text(f.info, f.get(exports)));
}

// Applies one registry keyword; false when `name` is none of them.
bool apply_registry_keyword(Keywords& into, const std::string& name, py::handle value,
                            unsigned groups) {
    if ((groups & (kUnitGroup | kFitGroup | kSweepGroup | kDecisionGroup)) != 0)
        if (const auto* f = find_option(analysis_option_table(), name);
            f != nullptr && (f->info.group & groups) != 0) {
            set_option(into.analysis, *f, option_value(f->info, value));
            return true;
        }
    if ((groups & kExportGroup) != 0)
        if (const auto* f = find_option(export_option_table(), name); f != nullptr) {
            set_option(into.exports, *f, option_value(f->info, value));
            return true;
        }
    return false;
}

const OptionInfo* registry_info(const std::string& name) {
    if (const auto* f = find_option(analysis_option_table(), name)) return &f->info;
    if (const auto* f = find_option(export_option_table(), name)) return &f->info;
    return nullptr;
}

// Whether a function of `groups` takes the keyword `name`.
bool accepts(unsigned groups, const std::string& name) {
    bool found = false;
    if ((groups & kSurfaceKeywords) != 0)
        for (const auto& k : surface_keywords()) found = found || name == k.name;
    for_each_registry_keyword(groups, [&](const OptionInfo& info, const std::string&) {
        found = found || info.name == name;
    });
    return found || (name == "force" && (groups & kForceKeyword) != 0);
}

}  // namespace

std::string keyword_names(unsigned groups) {
    std::string names;
    auto add = [&](std::string_view n) { names += (names.empty() ? "" : ", ") + std::string(n); };
    if ((groups & kSurfaceKeywords) != 0)
        for (const auto& k : surface_keywords()) add(k.name);
    for_each_registry_keyword(groups,
                              [&](const OptionInfo& info, const std::string&) { add(info.name); });
    if ((groups & kForceKeyword) != 0) add("force");
    return names;
}

std::string keyword_docs(unsigned groups) {
    std::string doc;
    if ((groups & kSurfaceKeywords) != 0)
        for (const auto& k : surface_keywords())
            doc += "    " + std::string(k.name) + ": " + k.expected + " — " + k.help + "\n";
    for_each_registry_keyword(groups, [&](const OptionInfo& info, const std::string& def) {
        doc += "    " + std::string(info.name) + ": " + kind_name(info.kind) + " = " +
               python_default(info.kind, def) +
               (info.unit.empty() ? "" : " [" + std::string(info.unit) + "]") + " — " +
               std::string(info.help) + "; " + describe_expected(info) + "\n";
    });
    if ((groups & kForceKeyword) != 0)
        doc +=
            "    force: bool = False — replace an existing output folder (only once the new "
            "results are complete)\n";
    return doc;
}

namespace {

// `text` when it reads as a Python literal inspect.signature accepts, else None (an infinite or
// otherwise unusual default stays the library's).
std::string literal_or_none(const std::string& text) {
    static const std::regex literal(
        R"(None|True|False|'[^'\\]*'|-?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?|\[[-0-9., eE+]*\])");
    return std::regex_match(text, literal) ? text : "None";
}

}  // namespace

std::string keyword_signature(unsigned groups) {
    std::vector<std::string> parts;
    if ((groups & kSurfaceKeywords) != 0)
        for (const auto& k : surface_keywords()) parts.push_back(std::string(k.name) + "=None");
    for_each_registry_keyword(groups, [&](const OptionInfo& info, const std::string& def) {
        parts.push_back(std::string(info.name) + "=" +
                        literal_or_none(python_default(info.kind, def)));
    });
    if ((groups & kForceKeyword) != 0) parts.emplace_back("force=False");
    std::string out;
    for (const auto& p : parts) out += (out.empty() ? "" : ", ") + p;
    return out;
}

void apply_keywords(Keywords& into, const py::kwargs& kwargs, unsigned groups,
                    const std::string& function) {
    for (const auto& [key, value] : kwargs) {
        const auto name = py::cast<std::string>(key);
        if (value.is_none()) {
            // None: the library's default. An unknown keyword is still an error.
            if (!accepts(groups, name))
                throw py::type_error(function + "() got an unexpected keyword argument '" + name +
                                     "'; it takes: " + keyword_names(groups));
            continue;
        }
        try {
            if (apply_registry_keyword(into, name, value, groups)) continue;
            if (name == "force" && (groups & kForceKeyword) != 0) {
                into.force = as<bool>(value);
                continue;
            }
            const SurfaceKeyword* surface = nullptr;
            if ((groups & kSurfaceKeywords) != 0)
                for (const auto& k : surface_keywords())
                    if (name == k.name) surface = &k;
            if (surface == nullptr)
                throw py::type_error(function + "() got an unexpected keyword argument '" + name +
                                     "'; it takes: " + keyword_names(groups));
            try {
                surface->apply(into.surface, value);
            } catch (const py::cast_error&) {
                throw InputError(function + ": " + name + " = " +
                                 py::cast<std::string>(py::repr(value)) + ": expected " +
                                 surface->expected);
            }
        } catch (const py::cast_error&) {
            const OptionInfo* info = registry_info(name);
            throw InputError(function + ": " + name + " = " +
                             py::cast<std::string>(py::repr(value)) + ": expected " +
                             (info ? describe_expected(*info) : std::string("a bool")));
        } catch (const OptionError& e) {
            // The registry names the option by its flag or key; Python names the keyword.
            const OptionInfo* info = registry_info(name);
            throw InputError(function + ": " + name + " = " +
                             py::cast<std::string>(py::repr(value)) + ": expected " +
                             (info ? describe_expected(*info) : std::string(e.what())));
        } catch (const InputError& e) {
            throw InputError(function + ": " + name + ": " + e.what());
        }
    }
}

std::string keyword_of_option(const std::string& path) {
    for (const auto& f : analysis_option_table())
        if (f.info.path() == path) return std::string(f.info.name);
    for (const auto& f : export_option_table())
        if (f.info.path() == path) return std::string(f.info.name);
    return "";
}

std::string options_json(const Keywords& k) { return to_json(k.analysis, k.exports); }

}  // namespace glint::python
