#include "analysis/units.h"

#include "mesh/error.h"
#include "mesh/front_end.h"
#include "mesh/units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

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

// The conversion between two known units nearest to `ratio` (reference size / examined size),
// when one lies within 10 %: {factor, "m → mm"}; else nothing. Of conversions with one factor
// (m → mm and mm → um are both 1000) the one into `into` (the analysis unit; mm when unknown).
struct UnitConversion {
    double factor = 1.0;
    std::string from, to;
};

std::optional<UnitConversion> nearest_conversion(double ratio, const std::string& into) {
    std::optional<UnitConversion> best;
    double best_gap = std::log(1.1);
    const std::string all = known_units();
    std::vector<std::string> names;
    for (std::size_t start = 0; start < all.size();) {
        std::size_t comma = all.find(", ", start);
        if (comma == std::string::npos) comma = all.size();
        names.push_back(all.substr(start, comma - start));
        start = comma + 2;
    }
    for (const auto& from : names)
        for (const auto& to : names) {
            if (from == to) continue;
            const double factor = *metres_per_unit(from) / *metres_per_unit(to);
            const double gap = std::abs(std::log(ratio / factor));
            const bool tie = best && std::abs(gap - best_gap) < 1e-9;
            if ((gap < best_gap && !tie) || (tie && to == into && best->to != into)) {
                best_gap = gap;
                best = UnitConversion{factor, from, to};
            }
        }
    return best;
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
    bool mismatch = !(lo > 0) || hi / lo > kMaxScaleRatio;
    const std::string into = r.unit.empty() ? "mm" : r.unit;
    if (mismatch && lo > 0 && hi / lo <= kMaxPartRatio &&
        !nearest_conversion(r.reference_size / r.examined_size, into)) {
        char b[300];
        std::snprintf(b, sizeof b,
                      "the %s mesh is %.3g× the size of the %s (bounding-box diagonals), a ratio "
                      "near no unit conversion: taken as a part against a whole (a crop, a "
                      "partial scan)",
                      r.examined_size > r.reference_size ? "examined" : "reference", hi / lo,
                      r.examined_size > r.reference_size ? "reference" : "examined");
        r.warnings.emplace_back(b);
        mismatch = false;
    }
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
        // Allowed: the examined proceeds at the unit conversion the ratio states (issue 53: a
        // reference in mm against an examined in m fitted nothing), refined by --fit-scale when
        // given; a ratio near no conversion is left to --fit-scale.
        const double ratio = r.reference_size / r.examined_size;
        if (const auto c = lo > 0 ? nearest_conversion(ratio, into) : std::nullopt) {
            r.examined_scale *= c->factor;
            r.examined_size *= c->factor;
            char b[240];
            std::snprintf(b, sizeof b,
                          "; the ratio %.4g is nearest the conversion %s → %s: the examined mesh "
                          "is taken as in %s and scaled by %g (%s fits the scale exactly)",
                          ratio, c->from.c_str(), c->to.c_str(), c->from.c_str(), c->factor,
                          spell_flag("fit_scale").c_str());
            r.warnings.push_back(what + "; allowed by " + spell_flag("allow_scale_mismatch") + b);
        } else {
            r.scale_unknown = lo > 0;
            r.warnings.push_back(what + "; allowed by " + spell_flag("allow_scale_mismatch") +
                                 "; the ratio is near no unit conversion: " +
                                 spell_flag("fit_scale") + " fits the scale");
        }
    }
    return r;
}

double starting_scale(const UnitResolution& u) {
    return u.scale_unknown && u.examined_size > 0 ? u.reference_size / u.examined_size : 1.0;
}

void scale_examined(Mesh& examined, double factor) {
    if (factor == 1.0) return;
    for (auto& p : examined.positions) p *= static_cast<float>(factor);
    if (examined.voxel_axes) *examined.voxel_axes *= factor;
    examined.field_of_view.scale(factor);
}

void scale_to_analysis_unit(Mesh& examined, const UnitResolution& units) {
    scale_examined(examined, units.examined_scale);
}

}  // namespace glint
