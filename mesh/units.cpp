#include "mesh/units.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <utility>

namespace glint {

namespace {

struct UnitName {
    const char* canonical;
    double metres;
    std::array<const char*, 8> spellings;  // lowercase, ASCII ("µ" is handled before lookup)
};

// note: only lengths people scan or segment anatomy and parts in; "ft" and "nm" are left out
// on purpose (a mesh in either is far more likely a mislabelled one).
constexpr std::array<UnitName, 5> kUnits{{
    {"um",
     1e-6,
     {"um", "micrometre", "micrometres", "micrometer", "micrometers", "micron", "microns", "mum"}},
    {"mm", 1e-3, {"mm", "millimetre", "millimetres", "millimeter", "millimeters", "", "", ""}},
    {"cm", 1e-2, {"cm", "centimetre", "centimetres", "centimeter", "centimeters", "", "", ""}},
    {"m", 1.0, {"m", "metre", "metres", "meter", "meters", "", "", ""}},
    {"in", 0.0254, {"in", "inch", "inches", "", "", "", "", ""}},
}};

std::string lower_ascii(std::string_view s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        // "µ" (U+00B5) and "μ" (U+03BC) in UTF-8 both become 'u'.
        if (i + 1 < s.size() &&
            ((s[i] == '\xC2' && s[i + 1] == '\xB5') || (s[i] == '\xCE' && s[i + 1] == '\xBC'))) {
            out.push_back('u');
            ++i;
            continue;
        }
        out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(s[i]))));
    }
    return out;
}

bool is_word(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (c & 0x80);
}

// In one comment line: "unit" or "units", then optional ':' / '=' / spaces, then a unit word.
std::string unit_in_line(std::string_view line) {
    const std::string l = lower_ascii(line);
    for (std::size_t at = l.find("unit"); at != std::string::npos; at = l.find("unit", at + 4)) {
        if (at > 0 && std::isalpha(static_cast<unsigned char>(l[at - 1]))) continue;
        std::size_t i = at + 4;
        if (i < l.size() && l[i] == 's') ++i;
        while (i < l.size() && (l[i] == ' ' || l[i] == '\t' || l[i] == ':' || l[i] == '=')) ++i;
        std::size_t j = i;
        while (j < l.size() && is_word(l[j])) ++j;
        std::string u = canonical_unit(std::string_view(l).substr(i, j - i));
        if (u == "in") {  // "unit in mm": the word after "in" is the unit
            std::size_t k = j;
            while (k < l.size() && (l[k] == ' ' || l[k] == '\t')) ++k;
            std::size_t e = k;
            while (e < l.size() && is_word(l[e])) ++e;
            if (std::string next = canonical_unit(std::string_view(l).substr(k, e - k));
                !next.empty())
                u = next;
        }
        if (!u.empty()) return u;
    }
    return "";
}

}  // namespace

std::string canonical_unit(std::string_view text) {
    const std::string t = lower_ascii(text);
    if (t.empty()) return "";
    for (const auto& u : kUnits)
        for (const char* s : u.spellings)
            if (*s && t == s) return u.canonical;
    return "";
}

std::optional<double> metres_per_unit(std::string_view unit) {
    for (const auto& u : kUnits)
        if (unit == u.canonical) return u.metres;
    return std::nullopt;
}

std::string known_units() {
    std::string out;
    for (const auto& u : kUnits) out += (out.empty() ? "" : ", ") + std::string(u.canonical);
    return out;
}

std::string unit_from_header(std::span<const char> head, const std::string& extension) {
    if (extension == ".gltf" || extension == ".glb") return "m";  // glTF 2.0: "units … are meters"
    const std::string_view text(head.data(), head.size());
    if (extension == ".stl" && !text.starts_with("solid")) return unit_in_line(text.substr(0, 80));
    const bool ply = text.starts_with("ply");
    const bool vtk = text.starts_with("# vtk DataFile");
    std::size_t pos = 0;
    for (int line_no = 0; pos < text.size(); ++line_no) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(pos, end - pos);
        pos = end + 1;
        if (ply && line.starts_with("end_header")) break;
        const bool comment = line.starts_with("#") || (ply && line.starts_with("comment")) ||
                             (vtk && line_no == 1) || (line_no == 0 && line.starts_with("solid"));
        if (!comment) continue;
        if (std::string u = unit_in_line(line); !u.empty()) return u;
        // 3D Slicer writes its models' coordinates in millimetres and says so only by naming
        // the patient space ("3D Slicer output. SPACE=LPS"): a skull exported from Slicer was
        // reported in "units" (issue 51).
        const std::string l = lower_ascii(line);
        if (l.find("space=lps") != std::string::npos || l.find("space=ras") != std::string::npos)
            return "mm";
    }
    return "";
}

std::string with_unit(double value, const std::string& unit, int power, const char* format) {
    char number[64];
    std::snprintf(number, sizeof number, format, value);
    static constexpr const char* kPower[] = {"", "", "²", "³"};
    return std::string(number) + " " + (unit.empty() ? std::string("units") : unit) +
           kPower[std::clamp(power, 0, 3)];
}

std::string unit_suffix(const std::string& unit, int power) {
    return "_" + (unit.empty() ? std::string("units") : unit) +
           (power > 1 ? std::to_string(power) : std::string());
}

}  // namespace glint
