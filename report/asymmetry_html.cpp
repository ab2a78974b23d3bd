#include "report/asymmetry_html.h"

#include "mesh/units.h"
#include "report/report_html.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace glint {

namespace {

using nlohmann::json;

// A number of report.json for people: 4 significant digits; "–" for null (no depth or volume
// where the mirror has no surface).
std::string number_text(const json& value) {
    if (!value.is_number()) return "\u2013";
    char b[40];
    std::snprintf(b, sizeof b, "%.4g", value.get<double>() + 0.0);
    return b;
}

// A normal or a point, to 6 decimals: a fitted plane's 1e-10 is 0.
std::string triple(const json& v) {
    std::string out = "(";
    for (std::size_t k = 0; k < 3; ++k)
        out += (k ? ", " : "") + (v[k].is_number()
                                      ? number_text(std::round(v[k].get<double>() * 1e6) / 1e6)
                                      : number_text(v[k]));
    return out + ")";
}

std::string row(const std::string& name, const std::string& value) {
    return "<tr><th>" + escape_markup(name) + "</th><td>" + escape_markup(value) + "</td></tr>\n";
}

std::string plane_table(const json& p, const std::string& unit) {
    const json& a = p["angle_to_axes_deg"];
    std::string t = "<table id=\"asymmetry-plane\"><tbody>\n";
    t += row("normal", triple(p["normal"]));
    t += row("point (" + unit + ")", triple(p["point"]));
    t += row("angle of the normal to the file's x, y, z axes", number_text(a[0]) + "\u00b0, " +
                                                                   number_text(a[1]) + "\u00b0, " +
                                                                   number_text(a[2]) + "\u00b0");
    t += row("residual (RMS of the mirrored surface on the surface)",
             p.value("residual_text", with_unit(p.value("residual", 0.0), unit)));
    t += row("overlap", number_text(100.0 * p.value("overlap", 0.0)) + " %");
    t += row("found by", p.value("source", ""));
    t += row("verdict", p.value("verdict", ""));
    return t + "</tbody></table>\n";
}

std::string findings_table(const json& findings, const std::string& unit) {
    const std::string l = " (" + unit + ")";
    std::string t =
        "<table id=\"asymmetry-findings\"><thead><tr><th>side</th><th>kind</th>"
        "<th>depth" +
        escape_markup(l) + "</th><th>area (" + escape_markup(unit) + "\u00b2)</th><th>volume (" +
        escape_markup(unit) + "\u00b3)</th><th>finding</th></tr></thead><tbody>\n";
    if (findings.empty())
        t += "<tr><td colspan=\"6\">no finding: the two sides agree within the floors</td></tr>\n";
    for (std::size_t i = 0; i < findings.size(); ++i) {
        const json& f = findings[i];
        t += "<tr data-finding=\"" + std::to_string(i) + "\" data-region=\"" +
             std::to_string(f.value("region", 0)) + "\"><td>" + escape_markup(f.value("side", "")) +
             "</td><td>" + escape_markup(f.value("kind", "")) + "</td><td>" +
             number_text(f["depth"]) + "</td><td>" + number_text(f["area"]) + "</td><td>" +
             number_text(f["volume"]) + "</td><td>" + escape_markup(f.value("text", "")) +
             "</td></tr>\n";
    }
    return t + "</tbody></table>\n";
}

}  // namespace

std::string asymmetry_section_html(const json& report) {
    if (!report.contains("asymmetry") || !report["asymmetry"].is_object()) return "";
    const json& a = report["asymmetry"];
    const std::string unit = report.contains("unit") && report["unit"].is_string()
                                 ? report["unit"].get<std::string>()
                                 : "units";
    std::string s =
        "<section id=\"asymmetry-panel\">\n<h2>Asymmetry: each side against the "
        "mirrored other side</h2>\n";
    s += "<p id=\"asymmetry-caveat\" class=\"caveat\">" +
         escape_markup("Caution: " + a.value("caveat", std::string()) + ".") + "</p>\n";
    s += "<h3>Symmetry plane</h3>\n";
    if (a.contains("plane")) s += plane_table(a["plane"], unit);
    if (a.contains("symmetry_floor")) {
        const json& fl = a["symmetry_floor"];
        s += "<p id=\"asymmetry-floor\">" +
             escape_markup("Floor: the rest of the surface against its mirror image: " +
                           fl.value("spread_text", std::string()) + "." +
                           (fl.contains("min_detectable_text")
                                ? " The smallest one-sided change that can be told from it: " +
                                      fl["min_detectable_text"].get<std::string>() + "."
                                : std::string())) +
             "</p>\n";
    }
    s += "<h3>Findings, side by side</h3>\n";
    s += findings_table(a.value("findings", json::array()), unit);
    if (a.contains("regions_note"))
        s += "<p class=\"note\">" + escape_markup(a["regions_note"].get<std::string>()) + "</p>\n";
    return s + "</section>\n";
}

}  // namespace glint
