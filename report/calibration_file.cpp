// calibration.json: what `glint calibrate` writes and `glint sweep --calibration` reads.
#include "report/calibration_file.h"

#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/small_file.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace glint {

std::string to_json(const Calibration& c) {
    nlohmann::json ladder = nlohmann::json::array();
    for (const auto& r : c.ladder)
        ladder.push_back({{"footprint", r.footprint},
                          {"regions", r.regions},
                          {"max_mean_angle_deg", r.max_angle_deg}});
    const nlohmann::json j = {
        {"glint_calibration", 1},
        {"found", c.found},
        {"footprint", c.found ? nlohmann::json(c.footprint) : nlohmann::json(nullptr)},
        {"threshold_deg", c.threshold_deg},
        {"referential", c.referential},
        {"ladder", ladder}};
    return json_text(j, 2) + "\n";
}

Calibration read_calibration(const std::filesystem::path& path) {
    const std::string text = read_small_file(path, "calibration");
    protect_input(path);  // never an output of this process
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw InputError("calibration \"" + path.string() + "\": not valid JSON: " + e.what());
    }
    if (!j.contains("glint_calibration"))
        throw InputError("calibration \"" + path.string() +
                         "\": not a glint calibration (written by glint calibrate)");
    Calibration c;
    // note: a value of the wrong type or a missing key is bad input, not an internal error
    // (found by fuzz/fuzz_calibration).
    try {
        c.found = j.value("found", false);
        if (!c.found || !j["footprint"].is_number())
            throw InputError(
                "calibration \"" + path.string() +
                "\": found no footprint that hides the referential deformation; widen the ladder");
        c.footprint = j["footprint"].get<double>();
        c.threshold_deg = j.at("threshold_deg").get<double>();
        c.referential = j.value("referential", "");
    } catch (const nlohmann::json::exception& e) {
        throw InputError(
            "calibration \"" + path.string() + "\": " + e.what() +
            ", expected found (bool), footprint and threshold_deg (numbers), referential (text)");
    }
    return c;
}

}  // namespace glint
