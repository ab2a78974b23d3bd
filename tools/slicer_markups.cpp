// Slicer's ROI text and markups files, in LPS (tools/slicer_markups.h).
#include "tools/slicer_markups.h"

#include "mesh/error.h"
#include "mesh/parse.h"
#include "mesh/small_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>

namespace glint::cli {

namespace {

namespace fs = std::filesystem;

// Slicer names a coordinate system "LPS"/"RAS" (also lower case); old files wrote 0 (RAS) or 1
// (LPS) (vtkMRMLMarkupsStorageNode::GetCoordinateSystemFromString).
bool is_ras(const std::string& text, const std::string& where) {
    std::string upper;
    for (char c : text) upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (upper == "RAS" || upper == "0") return true;
    if (upper == "LPS" || upper == "1") return false;
    throw InputError(where + ": coordinate system \"" + text + "\", expected LPS or RAS");
}

Vec3d to_lps(const Vec3d& p, bool ras) { return ras ? Vec3d(-p.x(), -p.y(), p.z()) : p; }

std::string trim(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return std::string(s.substr(first, s.find_last_not_of(" \t\r") - first + 1));
}

std::string read_text(const fs::path& path) { return read_small_file(path, "markups"); }

// One markup of a .mrk.json file: {"coordinateSystem": "LPS", "controlPoints": [{"label": …,
// "position": [x, y, z]}, …]} (Slicer's markups schema, "markups" array).
std::vector<Vec3d> json_points(const nlohmann::json& markup, const std::string& where) {
    const bool ras = markup.contains("coordinateSystem") &&
                     is_ras(markup["coordinateSystem"].get<std::string>(), where);
    if (!markup.contains("controlPoints") || !markup["controlPoints"].is_array())
        throw InputError(where + ": markup has no \"controlPoints\" array");
    std::vector<Vec3d> out;
    for (const auto& point : markup["controlPoints"]) {
        const std::string which = where + ": control point " + std::to_string(out.size() + 1) +
                                  (point.contains("label") && point["label"].is_string()
                                       ? " (\"" + point["label"].get<std::string>() + "\")"
                                       : std::string());
        const auto position = point.find("position");
        if (position == point.end() || !position->is_array() || position->size() != 3 ||
            !std::all_of(position->begin(), position->end(),
                         [](const nlohmann::json& v) { return v.is_number(); }))
            throw InputError(which + ": \"position\" is " +
                             (position == point.end() ? "missing" : position->dump()) +
                             ", expected [x, y, z] (place the point in Slicer)");
        out.push_back(to_lps(Vec3d((*position)[0].get<double>(), (*position)[1].get<double>(),
                                   (*position)[2].get<double>()),
                             ras));
    }
    return out;
}

std::vector<Vec3d> read_mrk_json(const fs::path& path) {
    const std::string where = "markups \"" + path.string() + "\"";
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(read_text(path));
        if (!doc.is_object() || !doc.contains("markups") || !doc["markups"].is_array() ||
            doc["markups"].empty())
            throw InputError(where + ": no \"markups\" array, expected a Slicer .mrk.json file");
        // note: a point file from Slicer holds the one markups node the parameter names.
        return json_points(doc["markups"][0], where);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(where + ": " + e.what() + ", expected a Slicer .mrk.json file");
    }
}

// Slicer's markups CSV: "# CoordinateSystem = LPS", "# columns = id,x,y,z,…", then one point a
// line, "id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID".
std::vector<Vec3d> read_fcsv(const fs::path& path) {
    const std::string where = "markups \"" + path.string() + "\"";
    std::istringstream in(read_text(path));
    bool ras = false;
    std::vector<Vec3d> out;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string at = where + " line " + std::to_string(number);
        if (line.starts_with("#")) {
            const auto equals = line.find('=');
            if (equals != std::string::npos &&
                trim(std::string_view(line).substr(1, equals - 1)) == "CoordinateSystem")
                ras = is_ras(trim(std::string_view(line).substr(equals + 1)), at);
            continue;
        }
        if (trim(line).empty()) continue;
        std::vector<std::string> fields;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(trim(cell));
        if (fields.size() < 4)
            throw InputError(at + ": \"" + trim(line) + "\", expected id,x,y,z,…");
        const auto xyz =
            parse_number_list(fields[1] + "," + fields[2] + "," + fields[3], at + ": x,y,z");
        out.push_back(to_lps(Vec3d(xyz[0], xyz[1], xyz[2]), ras));
    }
    return out;
}

}  // namespace

bool is_slicer_region(const std::string& text) {
    return !text.empty() && (std::isdigit(static_cast<unsigned char>(text[0])) != 0 ||
                             text[0] == '-' || text[0] == '+' || text[0] == '.');
}

Roi parse_slicer_region(const std::string& text) {
    const std::string where = "ROI \"" + text + "\"";
    std::vector<double> v = parse_number_list(text, where);
    // Slicer appends the ROI's axes (x0,y0,z0,x1,…, row by row) only when they differ from the
    // identity by more than 1e-3 (vtkMRMLMarkupsROINode::GetObjectToNodeMatrixRotated).
    const auto is_identity = [&v] {
        for (std::size_t k = 0; k < 9; ++k)
            if (std::fabs(v[6 + k] - (k % 4 == 0 ? 1.0 : 0.0)) > 1e-3) return false;
        return true;
    };
    if (v.size() == 15 && is_identity()) v.resize(6);
    if (v.size() == 15)
        throw InputError(where +
                         ": the ROI is rotated, expected an axis-aligned ROI (reset its "
                         "orientation in Slicer's Markups module)");
    if (v.size() != 6)
        throw InputError(where + ": " + std::to_string(v.size()) +
                         " numbers, expected cx,cy,cz,rx,ry,rz (an ROI's centre and radius)");
    if (!(v[3] > 0 && v[4] > 0 && v[5] > 0))
        throw InputError(where + ": radius must be positive along x, y and z (the ROI is empty)");
    Roi roi;
    roi.shape = Roi::Shape::Box;
    roi.min = Vec3d(v[0] - v[3], v[1] - v[4], v[2] - v[5]);
    roi.max = Vec3d(v[0] + v[3], v[1] + v[4], v[2] + v[5]);
    return roi;
}

std::vector<Vec3d> read_markups_points(const fs::path& path) {
    const std::string name = path.filename().string();
    const bool is_json = name.ends_with(".json");
    if (!is_json && !name.ends_with(".fcsv"))
        throw InputError("markups \"" + path.string() +
                         "\": unknown extension, expected .mrk.json or .fcsv");
    std::vector<Vec3d> points = is_json ? read_mrk_json(path) : read_fcsv(path);
    if (points.empty())
        throw InputError("markups \"" + path.string() +
                         "\": no control points, expected at least one");
    return points;
}

}  // namespace glint::cli
