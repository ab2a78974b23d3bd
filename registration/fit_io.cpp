#include "registration/fit_io.h"

#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/small_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

namespace glint {

std::string to_json(const RegistrationResult& r, const RegistrationOptions& o,
                    const RegistrationSources& sources) {
    auto matrix = [](const Rigid& t) {
        nlohmann::json rows = nlohmann::json::array();
        for (int i = 0; i < 4; ++i) rows.push_back({t(i, 0), t(i, 1), t(i, 2), t(i, 3)});
        return rows;
    };
    nlohmann::json log = nlohmann::json::array();
    for (const auto& l : r.log)
        log.push_back({{"iteration", l.iteration},
                       {"cost", l.cost},
                       {"rms", l.rms},
                       {"loss_scale", l.loss_scale},
                       {"overlap", l.overlap},
                       {"rotation_step_deg", l.rotation_step_deg},
                       {"translation_step", l.translation_step},
                       {"scale_step", l.scale_step}});
    auto vec = [](const Vec3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
    nlohmann::json roi;
    if (!o.roi) {
        roi = {{"shape", "none"}};
    } else if (o.roi->shape == Roi::Shape::Sphere) {
        roi = {{"shape", "sphere"}, {"center", vec(o.roi->center)}, {"radius", o.roi->radius}};
    } else if (o.roi->shape == Roi::Shape::Box) {
        roi = {{"shape", "box"}, {"min", vec(o.roi->min)}, {"max", vec(o.roi->max)}};
    } else {
        const auto on = std::count_if(o.roi->vertex_mask.begin(), o.roi->vertex_mask.end(),
                                      [](std::uint8_t m) { return m != 0; });
        roi = {{"shape", "vertex_mask"},
               {"file", o.roi->mask_file.string()},
               {"property", o.roi->mask_property},
               {"vertices", o.roi->vertex_mask.size()},
               {"masked_vertices", on}};
    }
    const nlohmann::json initial = o.initial ? matrix(*o.initial) : nlohmann::json(nullptr);
    const Eigen::AngleAxisd aa(Eigen::Matrix3d(r.reference_from_examined.linear()));
    // The similarity as one 4×4 matrix (what other tools read): the rigid part with its linear
    // block times the scale.
    Eigen::Matrix4d similarity = r.reference_from_examined.matrix();
    similarity.topLeftCorner<3, 3>() *= r.examined_scale;
    nlohmann::json similarity_rows = nlohmann::json::array();
    for (int i = 0; i < 4; ++i)
        similarity_rows.push_back(
            {similarity(i, 0), similarity(i, 1), similarity(i, 2), similarity(i, 3)});
    const nlohmann::json j = {
        {"reference_from_examined", matrix(r.reference_from_examined)},
        {"examined_from_reference", matrix(r.examined_from_reference)},
        {"examined_scale", r.examined_scale},
        {"examined_scale_uncertainty", r.scale_uncertainty},
        {"similarity_reference_from_examined", similarity_rows},
        {"scale_trend", r.scale_trend},
        {"scale_trend_uncertainty", r.scale_trend_uncertainty},
        {"rotation_deg", aa.angle() * 180.0 / std::numbers::pi},
        {"rotation_axis", {aa.axis().x(), aa.axis().y(), aa.axis().z()}},
        {"translation",
         {r.reference_from_examined.translation().x(), r.reference_from_examined.translation().y(),
          r.reference_from_examined.translation().z()}},
        {"rms", r.rms},
        {"inlier_fraction", r.inlier_fraction},
        {"overlap", r.overlap},
        {"iterations", r.iterations},
        {"converged", r.converged},
        {"termination", r.termination},
        {"termination_detail", r.termination_detail},
        {"coarse", r.coarse},
        {"matched", r.reference_on_examined ? "reference samples on the examined surface"
                                            : "examined samples on the reference"},
        {"options",
         {{"loss", to_string(o.loss)},
          {"samples", o.samples},
          {"max_iterations", o.max_iterations},
          {"max_normal_angle_deg", o.max_normal_angle_deg},
          {"symmetric", o.symmetric},
          {"fit_scale", o.fit_scale},
          {"initial_scale", o.initial_scale},
          {"rotation_tolerance_deg", o.rotation_tolerance_deg},
          {"translation_tolerance", o.translation_tolerance},
          {"cost_tolerance", o.cost_tolerance},
          {"min_overlap", o.min_overlap},
          {"overlap_distance", o.overlap_distance},
          {"anneal", {o.anneal_start, o.anneal_end}},
          {"seed", o.seed},
          {"roi", roi},
          {"initial", initial},
          {"init_file", sources.init_file},
          {"landmarks_file", sources.landmarks_file}}},
        {"log", log},
    };
    return json_text(j, 2) + "\n";
}

namespace {
std::string row_text(const nlohmann::json& row) {
    std::string text;
    for (const auto& v : row) text += (text.empty() ? "" : " ") + json_text(v);
    return text;
}
}  // namespace

FittedMotion read_fit(const std::string& path) {
    const std::string text = read_small_file(path, "fit");
    protect_input(path);  // never an output of this process
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw InputError("fit \"" + path + "\": not valid JSON: " + e.what());
    }
    const auto& m =
        j.contains("reference_from_examined") ? j["reference_from_examined"] : nlohmann::json();
    if (!m.is_array() || m.size() != 4)
        throw InputError("fit \"" + path +
                         "\": expected \"reference_from_examined\" as a 4×4 array of rows");
    Rigid t = Rigid::Identity();
    for (int r = 0; r < 4; ++r) {
        if (!m[static_cast<std::size_t>(r)].is_array() ||
            m[static_cast<std::size_t>(r)].size() != 4)
            throw InputError("fit \"" + path + "\": row " + std::to_string(r + 1) +
                             " of reference_from_examined is not 4 numbers");
        for (int c = 0; c < 4; ++c) {
            // note: a non-number here threw nlohmann's type_error (exit 4); found by fuzz/fuzz_fit.
            const auto& v = m[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
            if (!v.is_number())
                throw InputError("fit \"" + path + "\": row " + std::to_string(r + 1) +
                                 " of reference_from_examined: entry " + std::to_string(c + 1) +
                                 " is " + v.type_name() + ", expected a number");
            const double x = v.get<double>();
            if (!std::isfinite(x))
                throw InputError("fit \"" + path + "\": row " + std::to_string(r + 1) +
                                 " of reference_from_examined: entry " + std::to_string(c + 1) +
                                 " is not finite, expected a number");
            // Issue 23 item 15: a bottom row of "5 6 7 8" was taken as 0 0 0 1 without a word.
            if (r == 3 && x != (c == 3 ? 1.0 : 0.0))
                throw InputError("fit \"" + path + "\": row 4 of reference_from_examined is " +
                                 row_text(m[3]) +
                                 ", expected 0 0 0 1 (a rigid motion's homogeneous row)");
            t(r, c) = x;
        }
    }
    const Eigen::Matrix3d rot = t.linear();
    // note: 1e-6 tolerates the rounding of a matrix printed with ~10 digits.
    if (!(rot.transpose() * rot).isApprox(Eigen::Matrix3d::Identity(), 1e-6) ||
        std::abs(rot.determinant() - 1) > 1e-6)
        throw InputError(
            "fit \"" + path +
            "\": reference_from_examined is not a rigid motion (rotation part not orthonormal)");
    FittedMotion out{t, 1.0};
    if (j.contains("examined_scale")) {
        const auto& v = j["examined_scale"];
        if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>()))
            throw InputError("fit \"" + path + "\": examined_scale is " + json_text(v) +
                             ", expected a finite number > 0");
        out.examined_scale = v.get<double>();
    }
    return out;
}

}  // namespace glint
