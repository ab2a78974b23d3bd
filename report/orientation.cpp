#include "report/orientation.h"

#include "mesh/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>

namespace glint {

namespace {

struct AxisName {
    Vec3d direction;
    const char* lps;
    const char* ras;
    const char* plain;
};

const std::array<AxisName, 6> kAxes = {{
    {{1, 0, 0}, "left", "right", "+x"},
    {{-1, 0, 0}, "right", "left", "-x"},
    {{0, 1, 0}, "posterior", "anterior", "+y"},
    {{0, -1, 0}, "anterior", "posterior", "-y"},
    {{0, 0, 1}, "superior", "superior", "+z"},
    {{0, 0, -1}, "inferior", "inferior", "-z"},
}};

const char* axis_name(const AxisName& a, PatientSpace space) {
    return space == PatientSpace::LPS ? a.lps : space == PatientSpace::RAS ? a.ras : a.plain;
}

Vec3d named_axis(PatientSpace space, std::string_view name) {
    for (const auto& a : kAxes)
        if (axis_name(a, space) == name) return a.direction;
    return Vec3d::Zero();
}

Vec3d parse_up(std::string_view up) {
    const std::string_view axis = up.size() == 2 ? up.substr(1) : up;
    const double sign = up.front() == '-' ? -1.0 : 1.0;
    Vec3d d = Vec3d::Zero();
    d[axis == "x" ? 0 : axis == "y" ? 1 : 2] = sign;
    return d;
}

}  // namespace

std::string to_string(PatientSpace space) {
    return space == PatientSpace::LPS ? "LPS" : space == PatientSpace::RAS ? "RAS" : "";
}

PatientSpace parse_space(std::string_view text) {
    return text == "LPS"   ? PatientSpace::LPS
           : text == "RAS" ? PatientSpace::RAS
                           : PatientSpace::Unknown;
}

PatientSpace space_stated_in(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string head(4096, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
    const std::size_t at = head.find("SPACE=");
    if (at == std::string::npos || at + 9 > head.size()) return PatientSpace::Unknown;
    return parse_space(std::string_view(head).substr(at + 6, 3));
}

const std::vector<std::string>& up_choices() {
    static const std::vector<std::string> choices = {"+x", "x",  "-x", "+y", "y",
                                                     "-y", "+z", "z",  "-z"};
    return choices;
}

std::string Orientation::name(const Vec3d& direction) const {
    Vec3d d = direction.normalized();
    if (space != PatientSpace::Unknown) d.z() *= superior_sign;
    std::vector<std::pair<double, const char*>> parts;
    for (const auto& a : kAxes) {
        const double c = d.dot(a.direction);
        // note: 0.38 ≈ sin 22.5°: a component below it is not named (an octant's half).
        if (c >= 0.38) parts.emplace_back(c, axis_name(a, space));
    }
    std::stable_sort(parts.begin(), parts.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    std::string out;
    const bool anatomical = space != PatientSpace::Unknown;
    for (const auto& [c, n] : parts)
        out += (out.empty() || !anatomical ? "" : "-") + std::string(n);
    return out;
}

std::string Orientation::letter(const Vec3d& direction_in) const {
    Vec3d direction = direction_in;
    if (space != PatientSpace::Unknown) direction.z() *= superior_sign;
    const AxisName* best = &kAxes[0];
    for (const auto& a : kAxes)
        if (direction.dot(a.direction) > direction.dot(best->direction)) best = &a;
    if (space == PatientSpace::Unknown) return best->plain;
    const std::string n = axis_name(*best, space);
    return std::string(1, static_cast<char>(std::toupper(static_cast<unsigned char>(n[0]))));
}

Orientation resolve_orientation(PatientSpace space, std::string_view up) {
    if (!up.empty() &&
        std::find(up_choices().begin(), up_choices().end(), up) == up_choices().end())
        throw OptionError("exports.up", "\"" + std::string(up) + "\"",
                          "expected one of +x, -x, +y, -y, +z, -z");
    Orientation o;
    o.space = space;
    const std::string stated = to_string(space);
    if (!up.empty()) {
        o.up = parse_up(up);
        o.up_known = true;
        o.source = "drawn with " + std::string(up) + " up, as given";
        const Vec3d superior = named_axis(space, "superior");
        if (space != PatientSpace::Unknown && o.up.dot(superior) < -0.5) {
            // The given up is the space's inferior: a header written by hand whose slices run
            // downwards (CThead's). The head is upside down in the file, not turned: up is
            // named superior and left, right, anterior and posterior keep their names.
            o.superior_sign = -1.0;
            o.source += "; the reference states " + stated +
                        " patient space with its slices running downwards, so " + std::string(up) +
                        " is named superior and the other directions as stated";
        } else if (space != PatientSpace::Unknown && o.up.dot(superior) < 0.5) {
            // The file's space and the given up disagree otherwise (turned axes): neither
            // names directions then.
            o.space = PatientSpace::Unknown;
            o.source += "; the reference states " + stated + " patient space, where " +
                        o.name(o.up) + " is not superior, so directions are named by axis";
        }
    } else if (space != PatientSpace::Unknown) {
        o.up = named_axis(space, "superior");
        o.up_known = true;
        o.source = "the reference is in " + stated +
                   " patient space (a volume's physical space or the file's SPACE=): superior up, "
                   "seen from the front first";
    } else {
        o.source =
            "the reference does not state its orientation: +z drawn up, directions named by axis "
            "(give --up to say which way is up)";
    }
    // The first panel: from the front (anterior) in a patient space, else along +x; the first
    // candidate not along up.
    const std::array<Vec3d, 3> fronts =
        space != PatientSpace::Unknown
            ? std::array<Vec3d, 3>{named_axis(space, "anterior"), named_axis(space, "left"),
                                   named_axis(space, "superior")}
            : std::array<Vec3d, 3>{Vec3d::UnitX(), Vec3d::UnitY(), Vec3d::UnitZ()};
    for (const auto& f : fronts)
        if (std::abs(f.dot(o.up)) < 0.5) {
            o.front = f;
            break;
        }
    return o;
}

Vec3d panel_direction(const Orientation& o, double azimuth_deg, double elevation_deg) {
    Eigen::Matrix3d world_from_display;
    world_from_display.col(0) = o.front;
    world_from_display.col(1) = o.up.cross(o.front);
    world_from_display.col(2) = o.up;
    return world_from_display * direction_from_az_el(azimuth_deg, elevation_deg);
}

Vec3d up_hint(const Orientation& o, const Vec3d& direction) {
    // note: within ~2.6° of up, the projection of up onto the image is too short to roll by.
    return std::abs(direction.normalized().dot(o.up)) > 0.999 ? o.front : o.up;
}

View upright(const View& view, const Orientation& o) {
    View v = view;
    const Rigid& c = view.camera.world_from_camera;
    const Vec3d eye = c.translation();
    const Vec3d back = c.linear().col(2);  // from the target towards the camera
    v.camera.world_from_camera = look_at(eye, eye - back, up_hint(o, back));
    return v;
}

}  // namespace glint
