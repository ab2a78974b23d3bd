#include "report/finding.h"

#include "mesh/units.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace glint {

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
                            const std::string& unit) {
    const std::string area = with_unit(r.area, unit, 2, "%.3g");
    if (r.kind == RegionKind::MissingSurface)
        return "missing surface over " + area + " (the examined scan holds none there), " + place;
    const bool dent = r.kind == RegionKind::Dent;
    char depth[64];
    std::snprintf(depth, sizeof depth, "%.3g", std::abs(r.peak_depth));
    std::string s = std::string(dent ? "a dent " : "a bump ") + depth;
    if (uncertainty > 0) {
        char pm[64];
        std::snprintf(pm, sizeof pm, " ± %.2g", uncertainty);
        s += pm;
    }
    s += " " + (unit.empty() ? std::string("units") : unit) +
         (r.is_hole_loss() ? " deep at least"
          : dent           ? " deep"
                           : " high") +
         " over " + area;
    if (std::isfinite(r.volume) && r.volume != 0.0)
        s += " (" + with_unit(std::abs(r.volume), unit, 3, "%.3g") +
             (r.volume < 0 ? " lost)" : " gained)");
    return s + ", " + place;
}

}  // namespace glint
