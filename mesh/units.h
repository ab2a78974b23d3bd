// Length units: their names, their size, and where mesh files state them.
//
// A mesh file's coordinates are numbers; the unit is what makes "0.4" a 0.4 mm dent. Formats
// that carry one: glTF (metres, by its specification), and header comments some writers add
// (glint's PLY "comment unit mm", VTK title "… unit mm", OBJ/OFF "# units: mm", STL header
// "UNITS=mm"). Everything else is unknown ("") until the user states it (--unit).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace glint {

/// The canonical name of a length unit ("um", "mm", "cm", "m", "in") for one of its spellings
/// ("millimetre", "MM", "µm", "micron", "meters", "inch"…); "" when it is none of them.
[[nodiscard]] std::string canonical_unit(std::string_view text);

/// Metres per unit of a canonical unit name; nullopt for "" or an unknown name.
[[nodiscard]] std::optional<double> metres_per_unit(std::string_view unit);

/// The canonical names, for messages: "um, mm, cm, m, in".
[[nodiscard]] std::string known_units();

/// The unit a file's header states, or "": `head` is the file's first bytes (a few KiB),
/// `extension` its lowercase extension with the dot. Looks only where formats put comments:
/// PLY "comment" lines, lines starting with '#' (OBJ, OFF; VTK's title line too), the first
/// line of an ASCII STL and the 80-byte binary STL header; glTF/GLB are metres.
[[nodiscard]] std::string unit_from_header(std::span<const char> head,
                                           const std::string& extension);

/// `value` followed by the unit for people: "0.4 mm", "12 mm²" (power 2), "3 mm³"; with an
/// unknown unit "0.4 units". printf precision `format` ("%.4g").
[[nodiscard]] std::string with_unit(double value, const std::string& unit, int power = 1,
                                    const char* format = "%.4g");

/// Suffix for column and key names: "_mm", "_mm2", "_mm3"; "_units", "_units2" when unknown.
[[nodiscard]] std::string unit_suffix(const std::string& unit, int power = 1);

}  // namespace glint
