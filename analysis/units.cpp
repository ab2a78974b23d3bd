#include "analysis/units.h"

#include "mesh/error.h"
#include "mesh/front_end.h"
#include "mesh/units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace glint {

void UnitOptions::validate() const {
    if (!unit.empty() && canonical_unit(unit).empty())
        throw OptionError("unit", "\"" + unit + "\"",
                          "unknown length unit, expected one of " + known_units());
}

namespace {

std::string size_text(double size, const std::string& unit) {
    return with_unit(size, unit, 1, "%.4g");
}

// "the examined mesh is 1000× larger": the ratio in words for the message.
std::string ratio_text(double reference, double examined) {
    char b[96];
    if (examined >= reference)
        std::snprintf(b, sizeof b, "the examined mesh is %.4g× larger", examined / reference);
    else std::snprintf(b, sizeof b, "the examined mesh is %.4g× smaller", reference / examined);
    return b;
}

}  // namespace

UnitResolution resolve_units(const Mesh& reference, const Mesh& examined,
                             const UnitOptions& options) {
    options.validate();
    UnitResolution r;
    const std::string stated = canonical_unit(options.unit);
    const std::string ref_unit = canonical_unit(reference.unit);
    const std::string exa_unit = canonical_unit(examined.unit);
    if (!stated.empty()) {
        r.unit = stated;
        for (const auto& [role, u] :
             {std::pair{"reference", ref_unit}, std::pair{"examined", exa_unit}})
            if (!u.empty() && u != stated)
                r.warnings.push_back(std::string("the ") + role + " file states unit " + u + "; " +
                                     spell_option("unit", stated) + " was taken instead");
    } else if (!ref_unit.empty() && !exa_unit.empty() && ref_unit != exa_unit) {
        r.unit = ref_unit;
        r.examined_scale = *metres_per_unit(exa_unit) / *metres_per_unit(ref_unit);
        char b[160];
        std::snprintf(
            b, sizeof b,
            "the examined mesh is in %s, the reference in %s: examined scaled by %g into %s",
            exa_unit.c_str(), ref_unit.c_str(), r.examined_scale, ref_unit.c_str());
        r.warnings.emplace_back(b);
    } else {
        r.unit = !ref_unit.empty() ? ref_unit : exa_unit;
    }
    // In double: a float diagonal of coordinates near 1e20 overflows to inf.
    r.reference_size = bounds(reference).extent().cast<double>().norm();
    r.examined_size = bounds(examined).extent().cast<double>().norm() * r.examined_scale;
    const double lo = std::min(r.reference_size, r.examined_size),
                 hi = std::max(r.reference_size, r.examined_size);
    const bool mismatch = !(lo > 0) || hi / lo > kMaxScaleRatio;
    if (mismatch) {
        // Each size in the unit known for that mesh ("units" when its file states none).
        const std::string& ref_label = !stated.empty() ? stated : ref_unit;
        const std::string& exa_label = !stated.empty()           ? stated
                                       : r.examined_scale != 1.0 ? ref_unit
                                                                 : exa_unit;
        const std::string what =
            "mesh sizes differ: reference " + size_text(r.reference_size, ref_label) +
            ", examined " + size_text(r.examined_size, exa_label) + " (bounding-box diagonals; " +
            (lo > 0 ? ratio_text(r.reference_size, r.examined_size) : "one is empty") + ")";
        if (!(hi / lo <= kMaxAllowedScaleRatio))
            throw InputError(what + ", expected within " +
                             std::to_string(static_cast<int>(kMaxScaleRatio)) + "× (" +
                             spell_flag("allow_scale_mismatch") +
                             " allows up to 10^6×): convert one mesh "
                             "into the other's unit");
        if (!options.allow_scale_mismatch)
            throw InputError(
                what + ", expected within " + std::to_string(static_cast<int>(kMaxScaleRatio)) +
                "×: are they in different units (mm and m)? convert one into the other's unit, "
                "or give " +
                spell_flag("allow_scale_mismatch") + " to run anyway");
        r.warnings.push_back(what + "; allowed by " + spell_flag("allow_scale_mismatch"));
    }
    return r;
}

void scale_to_analysis_unit(Mesh& examined, const UnitResolution& units) {
    if (units.examined_scale == 1.0) return;
    for (auto& p : examined.positions) p *= static_cast<float>(units.examined_scale);
    if (examined.voxel_axes) *examined.voxel_axes *= units.examined_scale;
    examined.field_of_view.scale(units.examined_scale);
}

}  // namespace glint
