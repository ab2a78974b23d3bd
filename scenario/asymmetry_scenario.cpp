#include "scenario/asymmetry_scenario.h"

#include "mesh/error.h"
#include "scenario/detail/toml_reader.h"
#include "scenario/scenario.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace glint {

using detail::TableReader;

namespace {

// A plane = "…" text (parse_plane_spec's syntax), or the key's error with its line.
std::optional<SymmetryPlane> read_plane(TableReader& r, const char* key) {
    const auto text = r.optional<std::string>(key, "a string (x=C, point=…;normal=…, landmarks=…)");
    if (!text) return std::nullopt;
    try {
        return parse_plane_spec(*text);
    } catch (const InputError& e) {
        std::string what = e.what();  // "--plane \"q=1\": …": the key is named already
        if (what.starts_with("--plane ")) what.erase(0, 8);
        r.fail(r.get(key), key, what);
    }
}

FindingKindSide read_finding(TableReader& r) {
    FindingKindSide f;
    const auto kind =
        r.optional<std::string>("kind", "a string (less, more or no mirrored surface)");
    if (!kind) r.fail(nullptr, "kind", "missing: less, more or no mirrored surface");
    if (*kind != "less" && *kind != "more" && *kind != "no mirrored surface")
        r.fail(r.get("kind"), "kind",
               "\"" + *kind + "\": expected less, more or no mirrored surface");
    f.kind = *kind;
    const auto side = r.optional<std::string>("side", "a string (+x, -x, …, or left, right, …)");
    if (!side) r.fail(nullptr, "side", "missing: the side as report.json names it (+x, left, …)");
    f.side = *side;
    if (auto c = r.numbers("center", 3, 3)) f.center = Vec3d((*c)[0], (*c)[1], (*c)[2]);
    f.max_distance = r.positive("max_distance");
    if (f.center.has_value() != f.max_distance.has_value()) {
        const char* key = f.center ? "center" : "max_distance";
        r.fail(r.get(key), key, "center = [x, y, z] and max_distance go together");
    }
    r.finish();
    return f;
}

std::string number(const char* format, double v) {
    char b[64];
    std::snprintf(b, sizeof b, format, v);
    return b;
}

}  // namespace

bool AsymmetryExpect::any() const {
    return findings || min_findings || max_findings || !each.empty() || plane ||
           max_plane_angle_deg || max_plane_offset || no_plane;
}

void read_asymmetry_expect(TableReader& r, AsymmetryExpect& x) {
    auto count = [&](const char* key, std::optional<std::size_t>& out) {
        if (auto v = r.integer(key, 0, 1 << 30)) out = static_cast<std::size_t>(*v);
    };
    count("findings", x.findings);
    count("min_findings", x.min_findings);
    count("max_findings", x.max_findings);
    x.plane = read_plane(r, "plane");
    x.max_plane_angle_deg = r.positive("max_plane_angle_deg");
    x.max_plane_offset = r.positive("max_plane_offset");
    if (x.plane && (!x.max_plane_angle_deg || !x.max_plane_offset))
        r.fail(r.get("plane"), "plane", "needs max_plane_angle_deg and max_plane_offset");
    if (!x.plane && (x.max_plane_angle_deg || x.max_plane_offset)) {
        const char* key = x.max_plane_angle_deg ? "max_plane_angle_deg" : "max_plane_offset";
        r.fail(r.get(key), key, "needs plane = \"…\" (the expected plane)");
    }
    if (auto v = r.optional<bool>("no_plane", "true or false")) x.no_plane = *v;
    if (const toml::node* node = r.get("finding")) {
        const auto* arr = node->as_array();
        if (!arr || !arr->is_array_of_tables())
            r.fail(node, "finding", "expected [[expect.finding]] tables (kind, side)");
        for (std::size_t i = 0; i < arr->size(); ++i) {
            TableReader f(*(*arr)[i].as_table(), r.file(),
                          "expect.finding[" + std::to_string(i) + "]");
            x.each.push_back(read_finding(f));
        }
    }
    if (x.no_plane && (x.findings.value_or(0) > 0 || x.min_findings.value_or(0) > 0 ||
                       !x.each.empty() || x.plane))
        r.fail(r.get("no_plane"), "no_plane",
               "expects no plausible plane, so no plane and no findings can be expected");
}

void read_asymmetry_scenario(TableReader& top, Scenario& sc) {
    AsymmetrySpec& spec = sc.asymmetry;
    spec.enabled = top.optional<bool>("asymmetry", "true or false").value_or(false);
    spec.plane = read_plane(top, "plane");
    if (spec.plane && !spec.enabled)
        top.fail(top.get("plane"), "plane", "a symmetry plane needs asymmetry = true");
    if (!spec.enabled) {
        if (sc.expect.asymmetry.any())
            top.fail(top.get("expect"), "expect",
                     "findings, plane and no_plane expectations need asymmetry = true");
        return;
    }
    if (!sc.examined_derived || sc.examined.phantom)
        top.fail(top.get("examined"), "examined",
                 "asymmetry = true analyses the one surface of [reference]; [examined] names a "
                 "second one (mesh, phantom, scheme, resolution or size): remove it");
    // note: a resampled examined volume (erode, pose about a pivot, voxel_size, noise) is
    // how the one scan is made from the reference's volume: that scan is analysed.
}

std::pair<double, double> plane_difference(const SymmetryPlane& found,
                                           const SymmetryPlane& expected) {
    const double c = std::min(1.0, std::abs(found.normal.dot(expected.normal)));
    const double angle = std::acos(c) * 180.0 / std::numbers::pi;
    // Where the found plane crosses the expected plane's normal line through its point.
    const Vec3d p = expected.point();
    const double along = expected.normal.dot(found.normal);
    const double t = std::abs(along) > 1e-12 ? found.distance(p) / along : 0.0;
    return {angle, std::abs(t)};
}

void check_asymmetry_expect(const AsymmetryExpect& x, const AsymmetryOutcome& o,
                            std::vector<std::string>& failures) {
    if (x.no_plane) {
        if (o.plausible)
            failures.push_back("a plausible symmetry plane was found (" + o.verdict +
                               "), expected none");
        return;
    }
    if (!o.plausible) {
        if (x.any()) failures.push_back(o.verdict + ", expected a plausible symmetry plane");
        return;
    }
    const auto n = static_cast<double>(o.findings.size());
    if (x.findings && o.findings.size() != *x.findings)
        failures.push_back(number("findings = %.0f", n) +
                           number(", expected %.0f", double(*x.findings)));
    if (x.min_findings && o.findings.size() < *x.min_findings)
        failures.push_back(number("findings = %.0f", n) +
                           number(", expected at least %.0f", double(*x.min_findings)));
    if (x.max_findings && o.findings.size() > *x.max_findings)
        failures.push_back(number("findings = %.0f", n) +
                           number(", expected at most %.0f", double(*x.max_findings)));
    std::vector<bool> used(o.findings.size(), false);
    for (const FindingKindSide& e : x.each) {
        std::size_t i = 0;
        auto matches = [&](const FindingKindSide& f) {
            if (f.kind != e.kind || f.side != e.side) return false;
            return !e.center || (f.center && (*f.center - *e.center).norm() <= *e.max_distance);
        };
        while (i < o.findings.size() && (used[i] || !matches(o.findings[i]))) ++i;
        if (i < o.findings.size()) {
            used[i] = true;
            continue;
        }
        std::string found;
        auto place = [](const Vec3d& c) {
            char b[96];
            std::snprintf(b, sizeof b, " at (%.1f, %.1f, %.1f)", c.x(), c.y(), c.z());
            return std::string(b);
        };
        for (const auto& f : o.findings)
            found += (found.empty() ? "" : ", ") + f.kind + " on the " + f.side + " side" +
                     (e.center && f.center ? place(*f.center) : "");
        failures.push_back(
            "no finding '" + e.kind + "' on the " + e.side + " side" +
            (e.center ? place(*e.center) + number(" within %.3g", *e.max_distance) : "") +
            " (found: " + (found.empty() ? "none" : found) + ")");
    }
    if (x.plane && o.plane_angle_deg && *o.plane_angle_deg > *x.max_plane_angle_deg)
        failures.push_back(number("plane angle = %.4f°", *o.plane_angle_deg) +
                           number(", expected at most %.4f°", *x.max_plane_angle_deg));
    if (x.plane && o.plane_offset && *o.plane_offset > *x.max_plane_offset)
        failures.push_back(number("plane offset = %.4g", *o.plane_offset) +
                           number(", expected at most %.4g", *x.max_plane_offset));
}

}  // namespace glint
