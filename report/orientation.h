// Which way is up in the pictures, and what the directions are called (issue 24, item 3).
//
// A surface's coordinates may be a patient's: a volume's surface is in its physical space
// (volume/volume.h: origin + direction cosines · spacing · index), which ITK, DICOM and
// MetaImage define as LPS (+x left, +y posterior, +z superior); 3D Slicer states the space of
// the models it writes in their header ("SPACE=LPS" or "SPACE=RAS"). Then the pictures put
// superior up, look at the patient from the front first and name directions anatomically.
// A mesh that says nothing of its space is drawn with +z up and its directions are named by
// axis ("from +z"), never "top", unless the user says which way is up (--up -z).
//
//   space (input) ─┐
//   --up ──────────┴▶ Orientation ─▶ atlas.png panels and captions, per-view pictures and
//                                    mosaics (rolled so up is up), report.json "orientation",
//                                    report.html's camera
//
// The sweep itself is not changed: its views stay where the plan put them (scanner/plan.h);
// only how they are shown is rolled about the viewing axis.
#pragma once

#include "mesh/geometry.h"
#include "render/view.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// The patient coordinate system a surface's coordinates are in, when known.
enum class PatientSpace { Unknown, LPS, RAS };

/// "LPS", "RAS" or "" (unknown).
[[nodiscard]] std::string to_string(PatientSpace space);

/// "LPS" / "RAS" → that space; anything else Unknown.
[[nodiscard]] PatientSpace parse_space(std::string_view text);

/// The space a mesh file states in its first 4 KiB ("SPACE=LPS" / "SPACE=RAS", as 3D Slicer
/// writes it in VTK, PLY, OBJ and STL headers); Unknown when it states none or cannot be read.
[[nodiscard]] PatientSpace space_stated_in(const std::filesystem::path& path);

/// The accepted spellings of --up: "+x", "x", "-x", … "-z" (and "" = not given).
[[nodiscard]] const std::vector<std::string>& up_choices();

/// How the pictures are oriented.
struct Orientation {
    Vec3d up{0.0, 0.0, 1.0};     ///< unit, mesh coordinates: drawn up
    Vec3d front{1.0, 0.0, 0.0};  ///< unit, ⟂ up: the first overview panel looks from here
    PatientSpace space = PatientSpace::Unknown;
    bool up_known = false;  ///< the up direction is stated (a patient space or --up), not assumed
    /// +1, or −1 where --up named the space's inferior axis: a header whose slices run
    /// downwards (CThead's), so the given up is superior and the other names stay (issue 51).
    double superior_sign = 1.0;
    std::string source;  ///< how it was decided, one sentence (report.json, warnings)

    /// "superior", "left", … in a patient space, else "+z", "-x", … for a unit axis direction;
    /// an oblique direction is named by its main components ("anterior-left", "+x+z").
    [[nodiscard]] std::string name(const Vec3d& direction) const;
    /// "S", "L", … or "+z": the one-letter name of the axis nearest to `direction`.
    [[nodiscard]] std::string letter(const Vec3d& direction) const;
};

/// The orientation from the reference's space and --up ("" = not given).
/// \throw OptionError for an `up` not in up_choices().
[[nodiscard]] Orientation resolve_orientation(PatientSpace space, std::string_view up);

/// The view of an overview panel: from `front` turned by `azimuth_deg` about `up`, raised by
/// `elevation_deg` towards it, with `up` drawn up (looking along up: front drawn up).
[[nodiscard]] Vec3d panel_direction(const Orientation& o, double azimuth_deg, double elevation_deg);

/// The up hint for a camera looking from `direction` (towards the surface): `up`, or `front`
/// when the view looks along up.
[[nodiscard]] Vec3d up_hint(const Orientation& o, const Vec3d& direction);

/// The same camera rolled about its viewing axis so that `up` is drawn as close to up as the
/// view allows (what it sees is unchanged, only turned in the image).
[[nodiscard]] View upright(const View& view, const Orientation& o);

}  // namespace glint
