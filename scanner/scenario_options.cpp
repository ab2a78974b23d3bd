// Scenario files → AnalysisOptions: the same options, the same defaults as the command line.
#include "scanner/detail/scenario_options.h"

#include "mesh/error.h"

#include <algorithm>

namespace glint::detail {

namespace {

namespace fs = std::filesystem;

fs::path local_path(const fs::path& dir, const std::string& text) {
    const fs::path p(text);
    return p.is_absolute() ? p : dir / p;
}

// Runs a parser on a string key and turns its InputError into one naming file, line and key.
template <class Parse>
void parse_key(TableReader& r, const std::string& key, const char* expected, Parse parse) {
    if (auto v = r.optional<std::string>(key, expected)) {
        try {
            parse(*v);
        } catch (const InputError& e) {
            r.fail(r.get(key), key, e.what());
        }
    }
}

void read_registration(TableReader& r, const fs::path& dir, FitOptions& f) {
    parse_key(r, "mode", "a string (register, truth, identity, file)",
              [&](const std::string& v) { f.mode = parse_fit_mode(v); });
    parse_key(r, "loss", "a string (cauchy, huber, tukey, none)",
              [&](const std::string& v) { f.registration.loss = parse_loss(v); });
    parse_key(r, "roi", "a string (sphere:x,y,z,r, box:… or mask:FILE)", [&](const std::string& v) {
        Roi roi = parse_roi(v);
        if (roi.shape == Roi::Shape::VertexMask)
            roi.mask_file = local_path(dir, roi.mask_file.string());
        f.registration.roi = roi;
    });
    if (auto v = r.optional<bool>("symmetric", "a boolean")) f.registration.symmetric = *v;
    if (auto v = r.optional<bool>("coarse", "a boolean")) f.registration.coarse = *v;
    if (auto v = r.optional<std::int64_t>("samples", "an integer"))
        f.registration.samples = static_cast<int>(*v);
    if (auto v = r.optional<std::int64_t>("max_iterations", "an integer"))
        f.registration.max_iterations = static_cast<int>(*v);
    if (auto v = r.optional<std::string>("fit", "a string (a fit.json path)"))
        f.fit_file = local_path(dir, *v);
    if (auto v = r.optional<std::string>("landmarks", "a string (a landmarks JSON path)"))
        f.landmarks_file = local_path(dir, *v);
    if (auto v = r.optional<std::string>("init", "a string (a fit.json path)"))
        f.init_file = local_path(dir, *v);
}

void read_sweep(TableReader& r, const fs::path& dir, SweepOptions& s) {
    parse_key(r, "plan", "a string (rotary or sphere:N)",
              [&](const std::string& v) { parse_plan_kind(v, s.plan); });
    parse_key(r, "backend", "a string (auto, vulkan, embree)",
              [&](const std::string& v) { s.render.backend = parse_backend(v); });
    parse_key(r, "metric", "a string (angle or rgb)",
              [&](const std::string& v) { s.metric = parse_metric(v); });
    parse_key(r, "accumulate", "a string (auto, gpu, host)",
              [&](const std::string& v) { s.accumulate = parse_accumulation(v); });
    parse_key(r, "roi", "a string (sphere:x,y,z,r, box:… or mask:FILE)", [&](const std::string& v) {
        Roi roi = parse_roi(v);
        if (roi.shape == Roi::Shape::VertexMask)
            roi.mask_file = local_path(dir, roi.mask_file.string());
        s.plan.roi = roi;
    });
    if (auto v = r.optional<std::string>("device", "a string (Vulkan device name)"))
        s.render.device = *v;
    if (auto v = r.optional<double>("azimuth_step", "a number (degrees)"))
        s.plan.azimuth_step_deg = *v;
    if (auto v = r.numbers("elevations", 1, 64)) s.plan.elevations_deg = *v;
    if (auto v = r.numbers("zoom", 1, 16)) s.plan.footprints = *v;
    if (auto v = r.optional<std::int64_t>("size", "an integer (pixels)"))
        s.plan.size = static_cast<int>(*v);
    if (auto v = r.optional<std::int64_t>("supersample", "an integer"))
        s.render.supersample = static_cast<int>(*v);
    if (auto v = r.optional<double>("max_incidence", "a number (degrees)"))
        s.max_incidence_deg = *v;
}

void read_threshold(TableReader& r, DecisionOptions& d) {
    if (auto v = r.optional<double>("deg", "a number (metric units)")) d.threshold = *v;
    if (auto v = r.optional<double>("noise_k", "a number")) d.noise_k = *v;
    if (auto v = r.optional<double>("min_deg", "a number")) d.min_threshold = *v;
    if (auto v = r.optional<std::int64_t>("min_region_vertices", "an integer"))
        d.min_region_vertices = static_cast<std::size_t>(std::max<std::int64_t>(0, *v));
}

void read_decision(TableReader& r, DecisionOptions& d) {
    parse_key(r, "rule", "a string (fused or normal)",
              [&](const std::string& v) { d.rule = parse_decision_rule(v); });
    if (auto v = r.optional<double>("shape_threshold", "a number (mesh units)"))
        d.shape_threshold = *v;
    if (auto v = r.optional<double>("shape_k", "a number")) d.shape_k = *v;
    if (auto v = r.optional<double>("shape_low_k", "a number")) d.shape_low_k = *v;
    if (auto v = r.optional<double>("grow_fraction", "a number in (0, 1)")) d.grow_fraction = *v;
    if (auto v = r.optional<double>("max_plausible_deg", "a number"))
        d.max_plausible_threshold_deg = *v;
    if (auto v = r.optional<double>("max_plausible_shape_fraction", "a number"))
        d.max_plausible_shape_fraction = *v;
    if (auto v = r.optional<bool>("fill_holes", "a boolean")) d.fill_holes = *v;
}

}  // namespace

void read_analysis_sections(TableReader& top, const fs::path& dir, AnalysisOptions& options) {
    // Scenarios register unless told otherwise (the command line's default is to take the
    // meshes as aligned: a scenario with a pose always needs a fit).
    options.fit.mode = FitMode::Register;
    // The unit both meshes are in (scanner/units.h); phantoms are in mm.
    parse_key(top, "unit", "a string (um, mm, cm, m, in)", [&](const std::string& v) {
        options.units.unit = v;
        options.units.validate();
    });
    auto section = [&](const std::string& key, auto read) {
        const toml::node* node = top.get(key);
        if (!node) return;
        const auto* t = node->as_table();
        if (!t)
            top.fail(node, key,
                     "expected a section [" + key + "], found " + TableReader::type_name(*node));
        TableReader r(*t, top.file(), key);
        read(r);
        r.finish();
    };
    section("registration", [&](TableReader& r) { read_registration(r, dir, options.fit); });
    section("sweep", [&](TableReader& r) { read_sweep(r, dir, options.sweep); });
    section("threshold", [&](TableReader& r) { read_threshold(r, options.decision); });
    section("decision", [&](TableReader& r) { read_decision(r, options.decision); });
}

void validate_analysis_sections(const toml::table& root, const std::string& file,
                                const AnalysisOptions& options) {
    try {
        options.validate();
    } catch (const OptionError& e) {
        std::ostringstream s;
        s << "scenario \"" << file << "\"";
        if (const auto node = root.at_path(e.key()))
            s << " line " << node.node()->source().begin.line;
        s << ": " << e.what();
        throw InputError(s.str());
    }
}

}  // namespace glint::detail
