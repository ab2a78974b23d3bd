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
/// Sizes apart by more than kMaxScaleRatio but at most this, at a ratio near no conversion
/// between two units (within 10 %), are a part against a whole (a reference cropped around one
/// condyle against the whole jaw, issue 53: 6×): run, with a note. Near a conversion (10× for
/// cm → mm) they are refused as before.
inline constexpr double kMaxPartRatio = 20.0;
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
    /// Sizes apart beyond what a part against a whole explains, at no unit conversion, and
    /// allowed (--allow-scale-mismatch): a similarity fit starts from their ratio.
    bool scale_unknown = false;
};

/// The analysis unit of two meshes and the scale that brings the examined into it: a stated
/// unit wins; else when both files state units and they differ, the examined is converted
/// into the reference's unit (a warning says so); else the unit one file states.
/// \throw InputError when the sizes differ by more than kMaxScaleRatio and the options do not
/// allow it (the message names both sizes and the likely cause).
[[nodiscard]] UnitResolution resolve_units(const Mesh& reference, const Mesh& examined,
                                           const UnitOptions& options);

/// The examined surface's scale a similarity fit starts from: the ratio of the sizes when
/// units.scale_unknown (a mismatch --allow-scale-mismatch let through, no unit saying by how
/// much), else 1.
[[nodiscard]] double starting_scale(const UnitResolution& units);

/// Multiplies the examined mesh's positions, voxel axes and field of view by `factor` (about
/// the origin; nothing to do at 1).
void scale_examined(Mesh& examined, double factor);

/// Brings the examined mesh into the analysis unit: positions × units.examined_scale (nothing
/// to do at 1).
void scale_to_analysis_unit(Mesh& examined, const UnitResolution& units);

}  // namespace glint
