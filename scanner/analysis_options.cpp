// AnalysisOptions: checking every option before anything is loaded, and the options as JSON.
#include "scanner/analysis.h"

#include "mesh/error.h"

#include <nlohmann/json.hpp>

namespace glint {

namespace {

using nlohmann::json;

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

json path_or_null(const std::filesystem::path& p) {
    return p.empty() ? json(nullptr) : json(p.string());
}

json matrix_json(const Rigid& t) {
    json rows = json::array();
    for (int i = 0; i < 4; ++i) rows.push_back({t(i, 0), t(i, 1), t(i, 2), t(i, 3)});
    return rows;
}

std::string plan_kind(const SweepPlanOptions& p) {
    return p.kind == SweepPlanOptions::Kind::Rotary ? "rotary"
                                                    : "sphere:" + std::to_string(p.sphere_views);
}

json fit_json(const FitOptions& f) {
    const RegistrationOptions& r = f.registration;
    json j = {{"mode", to_string(f.mode)},
              {"fit", path_or_null(f.fit_file)},
              {"loss", to_string(r.loss)},
              {"roi", r.roi ? json(to_string(*r.roi)) : json(nullptr)},
              {"symmetric", r.symmetric},
              {"samples", r.samples},
              {"max_iterations", r.max_iterations},
              {"coarse", r.coarse},
              {"seed", r.seed},
              {"landmarks", path_or_null(f.landmarks_file)},
              {"init", path_or_null(f.init_file)}};
    if (f.mode == FitMode::Truth) j["truth"] = matrix_json(f.truth);
    return j;
}

json sweep_json(const SweepOptions& s) {
    const SweepPlanOptions& p = s.plan;
    return {{"plan", plan_kind(p)},
            {"azimuth_step", p.azimuth_step_deg},
            {"elevations", p.elevations_deg},
            {"zoom", p.footprints},
            {"size", p.size},
            {"margin", p.margin},
            {"roi", p.roi ? json(to_string(*p.roi)) : json(nullptr)},
            {"metric", to_string(s.metric)},
            {"backend", to_string(s.render.backend)},
            {"accumulate", to_string(s.accumulate)},
            {"device", s.render.device},
            {"supersample", s.render.supersample},
            {"max_incidence", s.max_incidence_deg},
            {"min_coverage", s.compare.min_coverage}};
}

json decision_json(const DecisionOptions& d) {
    return {{"rule", to_string(d.rule)},
            {"threshold", optional_number(d.threshold)},
            {"noise_k", d.noise_k},
            {"min_threshold", d.min_threshold},
            {"max_plausible_deg", d.max_plausible_threshold_deg},
            {"shape_threshold", optional_number(d.shape_threshold)},
            {"shape_k", d.shape_k},
            {"shape_low_k", d.shape_low_k},
            {"min_shape_fraction", d.min_shape_fraction},
            {"max_plausible_shape_fraction", d.max_plausible_shape_fraction},
            {"grow_fraction", d.grow_fraction},
            {"min_region_vertices", d.min_region_vertices},
            {"fill_holes", d.fill_holes}};
}

}  // namespace

AtlasFiles parse_atlas_files(std::string_view list, const std::string& key) {
    AtlasFiles files{.ply = false, .vtk = false, .vtp = false};
    std::size_t start = 0;
    while (start <= list.size()) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        const std::string_view name = list.substr(start, comma - start);
        bool* flag = name == "ply"   ? &files.ply
                     : name == "vtk" ? &files.vtk
                     : name == "vtp" ? &files.vtp
                                     : nullptr;
        if (flag == nullptr || *flag)
            throw OptionError(key, "\"" + std::string(list) + "\"",
                              flag == nullptr ? "expected a comma-separated list of ply, vtk, vtp"
                                              : "names " + std::string(name) + " twice");
        *flag = true;
        start = comma + 1;
    }
    return files;
}

std::string to_string(const AtlasFiles& files) {
    std::string out;
    for (const auto& [on, name] :
         {std::pair{files.ply, "ply"}, {files.vtk, "vtk"}, {files.vtp, "vtp"}})
        if (on) out += (out.empty() ? "" : ",") + std::string(name);
    return out;
}

void ExportOptions::validate() const {
    if (!atlas_files.ply && !atlas_files.vtk && !atlas_files.vtp)
        throw OptionError("exports.atlas_files", "none", "expected at least one of ply, vtk, vtp");
    if (mosaic_tile < 16 || mosaic_tile > 1024)
        throw OptionError("exports.mosaic_tile", mosaic_tile, "must be in [16, 1024] pixels");
    std::error_code ec;
    if (!output.empty() && !replace_existing && std::filesystem::exists(output, ec))
        throw InputError("output folder \"" + output.string() +
                         "\" exists; give --force to replace it (the new "
                         "results replace it only when the run completes)");
}

void AnalysisOptions::validate() const {
    units.validate();
    fit.validate();
    sweep.validate();
    decision.validate();
    exports.validate();
    const MetricDescriptor& m = describe(sweep.metric);
    if (decision.threshold && *decision.threshold > m.max_value)
        throw OptionError("threshold.deg", *decision.threshold,
                          "must be in (0, " + std::to_string(static_cast<int>(m.max_value)) + "] " +
                              std::string(m.unit) + " (metric " + std::string(m.name) + ")");
}

std::string to_json(const AnalysisOptions& o) {
    const json j = {{"units",
                     {{"unit", o.units.unit.empty() ? json(nullptr) : json(o.units.unit)},
                      {"allow_scale_mismatch", o.units.allow_scale_mismatch}}},
                    {"registration", fit_json(o.fit)},
                    {"sweep", sweep_json(o.sweep)},
                    {"decision", decision_json(o.decision)},
                    {"exports",
                     {{"views", o.exports.write_views},
                      {"exr", o.exports.write_exr},
                      {"atlas_files", to_string(o.exports.atlas_files)},
                      {"mosaic_tile", o.exports.mosaic_tile}}}};
    return j.dump(2);
}

}  // namespace glint
