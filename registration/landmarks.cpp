#include "registration/landmarks.h"

#include "mesh/error.h"
#include "mesh/output_guard.h"
#include "mesh/small_file.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace glint {

Rigid fit_landmarks(const std::vector<Vec3d>& examined, const std::vector<Vec3d>& reference) {
    if (examined.size() != reference.size())
        throw InputError("landmarks: " + std::to_string(examined.size()) + " examined points for " +
                         std::to_string(reference.size()) + " reference points, expected pairs");
    if (examined.size() < 3)
        throw InputError("landmarks: " + std::to_string(examined.size()) +
                         " pair(s), expected at least 3");
    Eigen::Matrix3Xd src(3, examined.size()), dst(3, reference.size());
    for (std::size_t i = 0; i < examined.size(); ++i) {
        src.col(static_cast<Eigen::Index>(i)) = examined[i];
        dst.col(static_cast<Eigen::Index>(i)) = reference[i];
    }
    for (const auto* m : {&src, &dst}) {
        const Eigen::Matrix3Xd centred = m->colwise() - m->rowwise().mean();
        const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(centred);
        const auto sv = svd.singularValues();
        // note: a second singular value below 1e-6 of the first means the points lie on a
        // line (to 1 µm in 1 m): the rotation about that line is undetermined.
        if (!(sv(1) > 1e-6 * sv(0)))
            throw InputError(
                "landmarks: the points are collinear (or coincide), a rotation about their line is undetermined");
    }
    Rigid t = Rigid::Identity();
    t.matrix() = Eigen::umeyama(src, dst, false);
    return t;
}

namespace {

// n numbers as `shape` ("[x, y, z]"), else one line naming the pair and what was found.
std::vector<double> json_numbers(const nlohmann::json& v, std::size_t n, const std::string& where,
                                 const std::string& what, const std::string& shape) {
    if (!v.is_array() || v.size() != n)
        throw InputError(where + ": " + what + " must be " + shape + ", found " +
                         (v.is_array() ? "an array of " + std::to_string(v.size())
                                       : std::string(v.type_name())));
    std::vector<double> out;
    for (const auto& x : v) {
        if (!x.is_number())
            throw InputError(where + ": " + what + " must be " + shape + " (numbers), found a " +
                             x.type_name());
        out.push_back(x.get<double>());
    }
    return out;
}

// A number of a landmark's view; `fallback` when optional and absent.
double view_number(const nlohmann::json& view, const char* field, bool required, double fallback,
                   const std::string& where, const std::string& what) {
    if (!view.contains(field)) {
        if (required) throw InputError(where + ": " + what + " view has no '" + field + "'");
        return fallback;
    }
    if (!view[field].is_number())
        throw InputError(where + ": " + what + " view '" + field + "' must be a number, found " +
                         view[field].type_name());
    return view[field].get<double>();
}

// One side of a pair: a point [x, y, z], or a pixel picked in a view.
LandmarkSide read_side(const nlohmann::json& p, const char* key, const std::string& where) {
    const std::string what = std::string("'") + key + "'";
    if (!p.contains(key))
        throw InputError(where + ": no " + what +
                         " (expected [x, y, z] or {\"view\": …, \"pixel\": [u, v]})");
    const auto& s = p[key];
    LandmarkSide out;
    if (s.is_array()) {
        const auto v = json_numbers(s, 3, where, what, "[x, y, z]");
        out.point = Vec3d(v[0], v[1], v[2]);
        return out;
    }
    if (!s.is_object() || !s.contains("view") || !s.contains("pixel") || !s["view"].is_object())
        throw InputError(where + ": " + what +
                         " must be [x, y, z] or {\"view\": {\"azimuth\": A, \"elevation\": E, "
                         "\"size\": N}, \"pixel\": [u, v]}");
    const auto px = json_numbers(s["pixel"], 2, where, what + " pixel", "[u, v]");
    out.u = px[0];
    out.v = px[1];
    const auto& view = s["view"];
    out.view.azimuth_deg = view_number(view, "azimuth", true, 0.0, where, what);
    out.view.elevation_deg = view_number(view, "elevation", true, 0.0, where, what);
    const double size = view_number(view, "size", true, 0.0, where, what);
    if (!(size >= 1 && size <= 1 << 16 && size == std::floor(size)))
        throw InputError(where + ": " + what + " view 'size' = " + std::to_string(size) +
                         ", expected a whole number of pixels ≥ 1");
    out.view.size = static_cast<int>(size);
    out.view.footprint = view_number(view, "footprint", false, 0.0, where, what);
    if (out.view.footprint < 0)
        throw InputError(where + ": " + what + " view 'footprint' must be > 0 (or left out)");
    return out;
}

}  // namespace

std::vector<LandmarkPair> read_landmarks(const std::string& path) {
    const std::string text = read_small_file(path, "landmarks");
    protect_input(path);  // never an output of this process
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw InputError("landmarks \"" + path + "\": not valid JSON: " + e.what());
    }
    if (!j.is_object() || !j.contains("pairs") || !j["pairs"].is_array())
        throw InputError(
            "landmarks \"" + path +
            "\": expected {\"pairs\": [{\"examined\": [x,y,z], \"reference\": [x,y,z]}, …]}");
    std::vector<LandmarkPair> pairs;
    std::size_t i = 0;
    for (const auto& p : j["pairs"]) {
        ++i;
        const std::string where = "landmarks \"" + path + "\": pair " + std::to_string(i);
        if (!p.is_object())
            throw InputError(where + ": expected {\"examined\": …, \"reference\": …}, found " +
                             p.type_name());
        pairs.push_back({read_side(p, "examined", where), read_side(p, "reference", where)});
    }
    return pairs;
}

}  // namespace glint
