#include "report/detail/footer.h"

#include "scanner/metric.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>

namespace glint::detail {

namespace {

constexpr int kFooterFont = 13;
constexpr int kFooterLine = 19;  // px per footer line
constexpr int kPad = 8;          // px above the first line and below the last

std::string unit_of(const AnalysisResult& r) { return r.unit.empty() ? "units" : r.unit; }

std::string fit_line(const AnalysisResult& r) {
    const FitOutcome& fit = r.fit;
    if (fit.mode == FitMode::Identity)
        return "fit: identity (the surfaces were given in one frame)";
    const Rigid& t = fit.reference_from_examined;
    const double angle_deg = Eigen::AngleAxisd(t.linear()).angle() * 180.0 / std::numbers::pi;
    const Vec3d shift = t.translation();
    const std::string u = unit_of(r);
    std::string line = fit.mode == FitMode::Register ? "fit: registered"
                       : fit.mode == FitMode::File   ? "fit: given (fit file)"
                                                     : "fit: given (known pose)";
    char b[200];
    std::snprintf(b, sizeof b, ", rotation %.2f\u00b0, translation %s %s (%s, %s, %s)", angle_deg,
                  format_number(shift.norm()).c_str(), u.c_str(), format_number(shift.x()).c_str(),
                  format_number(shift.y()).c_str(), format_number(shift.z()).c_str());
    line += b;
    if (fit.mode == FitMode::Register && fit.registration) {
        const RegistrationResult& reg = *fit.registration;
        std::snprintf(b, sizeof b, ", RMS %s %s, overlap %.0f %%%s", format_number(reg.rms).c_str(),
                      u.c_str(), 100.0 * reg.overlap, fit.converged ? "" : ", NOT CONVERGED");
        line += b;
    }
    return line;
}

std::string floors_line(const AnalysisResult& r) {
    if (r.decisions.empty()) return "floors: none (no decision)";
    const ZoomDecision& d = r.decisions[0];
    const MetricDescriptor& m = describe(r.sweep.options.metric);
    const std::string normal_unit = picture_unit_suffix(d.scale.radius > 0 ? "deg" : m.unit);
    char b[240];
    // note: past 90° two normals bound nothing a surface shows; the legend says the same
    // (report/pictures.cpp, issue 51).
    if (normal_unit == "\u00b0" && d.normal.value > 90.0)
        std::snprintf(b, sizeof b,
                      "floors (zoom 0, %s rule): normals none (they differ by %s° by nature)",
                      to_string(d.rule).c_str(), format_number(d.normal.value).c_str());
    else
        std::snprintf(b, sizeof b, "floors (zoom 0, %s rule): normal %s%s (%s)",
                      to_string(d.rule).c_str(), format_number(d.normal.value).c_str(),
                      normal_unit.c_str(), to_string(d.normal.source).c_str());
    std::string line = b;
    if (d.rule == DecisionRule::Fused) {
        std::snprintf(b, sizeof b, ", shape %s %s (%s)", format_number(d.shape.value).c_str(),
                      unit_of(r).c_str(), to_string(d.shape.source).c_str());
        line += b;
    }
    return line;
}

}  // namespace

std::vector<std::string> footer_lines(const AnalysisResult& result, const FooterInput& in) {
    const auto name = [](const std::string& n) { return n.empty() ? std::string("(unnamed)") : n; };
    return {"reference " + name(in.reference_name) + "  \u00b7  examined " +
                name(in.examined_name) + "  \u00b7  run " + in.date,
            fit_line(result), floors_line(result)};
}

std::string utc_date_now() {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char b[40];
    std::strftime(b, sizeof b, "%Y-%m-%d %H:%M UTC", &utc);
    return b;
}

int footer_height(std::size_t lines) { return 2 * kPad + static_cast<int>(lines) * kFooterLine; }

Canvas with_footer(const Canvas& sheet, const std::vector<std::string>& lines) {
    const int w = sheet.width(), h = sheet.height();
    Canvas out = canvas(w, h + footer_height(lines.size()));
    out.paste(sheet, 0, 0);
    draw_box(out, 0, h, w - 1, h, kDimText, true);  // a rule between the picture and its footer
    int y = h + kPad + kFooterFont;
    for (const auto& line : lines) {
        draw_text(out, 8, y, line, kFooterFont, kDimText);
        y += kFooterLine;
    }
    return out;
}

}  // namespace glint::detail
