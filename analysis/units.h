// The length unit of an analysis, and the check that both meshes are in it.
//
// Every length glint reports (depths, areas, volumes, footprints, distances) is in the
// reference mesh's unit. The unit comes from --unit (scenario key `unit`) when given, else
// from the files (mesh/units.h); unknown stays "" and is printed as "units". Two meshes whose
// sizes differ by more than kMaxScaleRatio are almost surely in different units (a reference
// in metres against an examined in mm): refused before any long work, with both sizes named.
#pragma once

#include "mesh/mesh.h"

#include <string>
#include <vector>

namespace glint {

/// Sizes (bounding-box diagonals) of the two meshes may differ by this factor at most.
/// note: 5× leaves room for a partial scan against a whole bone (a condyle against the
/// mandible is ~4×) while catching mm against cm (10×) and mm against m (1000×).
inline constexpr double kMaxScaleRatio = 5.0;
/// Beyond this ratio no run is meaningful, --allow-scale-mismatch or not: a mesh scaled by 1e20
/// spent minutes in closest-point queries before any message.
inline constexpr double kMaxAllowedScaleRatio = 1e6;

struct UnitOptions {
    /// The unit both meshes are in ("mm", "m", "um", "cm", "in"; mesh/units.h spellings);
    /// empty: what the files state. Given, it wins over the files (with a warning when a file
    /// states another).
    std::string unit;
    bool allow_scale_mismatch = false;  ///< run even when the sizes differ by > kMaxScaleRatio

    /// \throw OptionError for an unknown unit name.
    void validate() const;
};

struct UnitResolution {
    std::string unit;             ///< of the analysis ("" = unknown)
    double examined_scale = 1.0;  ///< multiply the examined positions by this (files in two units)
    double reference_size = 0.0;  ///< bounding-box diagonal, analysis unit
    double examined_size = 0.0;   ///< after examined_scale
    std::vector<std::string> warnings;  ///< unit conflicts, conversions, a mismatch allowed
};

/// The analysis unit of two meshes and the scale that brings the examined into it: a stated
/// unit wins; else when both files state units and they differ, the examined is converted
/// into the reference's unit (a warning says so); else the unit one file states.
/// \throw InputError when the sizes differ by more than kMaxScaleRatio and the options do not
/// allow it (the message names both sizes and the likely cause).
[[nodiscard]] UnitResolution resolve_units(const Mesh& reference, const Mesh& examined,
                                           const UnitOptions& options);

/// Brings the examined mesh into the analysis unit: positions × units.examined_scale (nothing
/// to do at 1).
void scale_to_analysis_unit(Mesh& examined, const UnitResolution& units);

}  // namespace glint
