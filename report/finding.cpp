#include "report/finding.h"

#include "mesh/units.h"
#include "report/detail/canvas.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace glint {

namespace {

// A quantity as a reader says it: three significant digits, no exponent below a million
// (7310 mm², not 7.31e+03 mm²).
std::string amount(double value, const std::string& unit, int power) {
    static constexpr const char* kPower[] = {"", "", "²", "³"};
    return detail::format_number(value) + " " + (unit.empty() ? std::string("units") : unit) +
           kPower[power];
}

}  // namespace

std::string region_place(const Region& region, const Bounds& reference, const Orientation& o) {
    std::vector<std::string> sides;
    if (!reference.is_empty()) {
        const Vec3d centre = reference.center().cast<double>();
        const Vec3d extent = reference.extent().cast<double>();
        // Left–right first, then front–back, then up–down: how a place on a body is said.
        for (const Vec3d& axis : {Vec3d(o.up.cross(o.front)), o.front, o.up}) {
            const Vec3d a = axis.normalized();
            const double half = 0.5 * a.cwiseAbs().dot(extent);
            if (!(half > 0)) continue;
            const double offset = (region.centroid - centre).dot(a) / half;
            if (offset > kPlaceOffset) sides.push_back(o.name(a));
            else if (offset < -kPlaceOffset) sides.push_back(o.name(-a));
        }
    }
    std::string out;
    for (const auto& s : sides) out += (out.empty() ? "" : ", ") + s;
    out += out.empty() ? "central part" : " part";
    if (region.view_direction.norm() > 0.5) {
        const std::string facing = o.name(region.view_direction);
        if (!facing.empty()) out += ", best seen from " + facing;
    }
    return out;
}

std::string region_sentence(const Region& r, const std::string& place, double uncertainty,
                            const std::string& unit, bool mirror) {
    const std::string area = amount(r.area, unit, 2);
    if (r.kind == RegionKind::MissingSurface)
        return mirror ? "no mirrored surface over " + area +
                            " (the other side holds none there), " + place
                      : "missing surface over " + area + " (the examined scan holds none there), " +
                            place;
    if (r.is_hole_loss()) {
        // Surface gone where the examined surface covered around it (a resection, a fracture,
        // worn-away material): its volume is the solid it bounds with its rim, its depth how
        // far it stood above that rim (the loss reaches at least that deep).
        std::string s = "surface gone over " + area + " (";
        if (std::isfinite(r.volume) && r.volume < 0)
            s += "about " + amount(-r.volume, unit, 3) + " lost; ";
        return s + "it stood up to " + amount(-r.peak_depth, unit, 1) +
               " above the rim of what remains), " + place;
    }
    const bool dent = r.kind == RegionKind::Dent;
    char depth[64];
    std::snprintf(depth, sizeof depth, "%.3g", std::abs(r.peak_depth));
    std::string s = mirror ? std::string(depth) : std::string(dent ? "a dent " : "a bump ") + depth;
    if (uncertainty > 0) {
        char pm[64];
        std::snprintf(pm, sizeof pm, " ± %.2g", uncertainty);
        s += pm;
    }
    s += " " + (unit.empty() ? std::string("units") : unit);
    if (mirror)
        s += dent ? " less than the mirrored other side" : " more than the mirrored other side";
    else s += dent ? " deep" : " high";
    s += " over " + area;
    if (std::isfinite(r.volume) && r.volume != 0.0)
        s += " (" + amount(std::abs(r.volume), unit, 3) +
             (mirror ? (r.volume < 0 ? " less)" : " more)")
                     : (r.volume < 0 ? " lost)" : " gained)"));
    return s + ", " + place;
}

std::string significance_text(double p) {
    if (!std::isfinite(p)) return "p unknown";
    if (p < 1e-6) return "family-wise p < 1e-6";
    char text[48];
    std::snprintf(text, sizeof text, "family-wise p = %.1g", p);
    return text;
}

}  // namespace glint
