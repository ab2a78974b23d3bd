// The options of a run as JSON (report.json's "analysis", --print-options), from the option
// tables: one object per TOML section, one member per key, so the printed options read as the
// scenario file that would give them.
#include "report/export_options.h"

#include "analysis/option_registry.h"
#include "mesh/json_text.h"
#include "report/detail/options_json.h"

#include <nlohmann/json.hpp>

namespace glint {

namespace {

using nlohmann::json;

json value_json(const OptionValue& value) {
    struct Visit {
        json operator()(std::monostate) const { return nullptr; }
        json operator()(bool b) const { return b; }
        json operator()(std::int64_t n) const { return n; }
        json operator()(double d) const { return d; }
        json operator()(const std::string& s) const { return s; }
        json operator()(const std::vector<double>& v) const { return v; }
    };
    return std::visit(Visit{}, value);
}

json& slot(json& root, const OptionInfo& info) {
    return info.section.empty() ? root[std::string(info.key)]
                                : root[std::string(info.section)][std::string(info.key)];
}

json path_or_null(const std::filesystem::path& p) {
    return p.empty() ? json(nullptr) : json(p.string());
}

json matrix_json(const Rigid& t) {
    json rows = json::array();
    for (int i = 0; i < 4; ++i) rows.push_back({t(i, 0), t(i, 1), t(i, 2), t(i, 3)});
    return rows;
}

}  // namespace

}  // namespace glint

namespace glint::detail {

nlohmann::json options_object(const AnalysisOptions& o, const ExportOptions& e) {
    using nlohmann::json;
    json j = json::object();
    // How the examined mesh was brought into the reference's frame (not a registry option).
    j["registration"]["mode"] = to_string(o.fit.mode);
    j["registration"]["fit"] = path_or_null(o.fit.fit_file);
    if (o.fit.mode == FitMode::Truth) j["registration"]["truth"] = matrix_json(o.fit.truth);
    for (const auto& f : analysis_option_table()) slot(j, f.info) = value_json(f.get(o));
    for (const auto& f : export_option_table()) slot(j, f.info) = value_json(f.get(e));
    return j;
}

}  // namespace glint::detail

namespace glint {

std::string to_json(const AnalysisOptions& o, const ExportOptions& e) {
    return json_text(detail::options_object(o, e), 2);
}

}  // namespace glint
