// A Slicer call: parse the flags and index arguments of the description, run the sweep,
// put atlas / regions / mosaic where Slicer asked, write the return parameters, and report
// progress on stdout (tools/slicer_module.h).
#include "mesh/atomic_file.h"
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/geometry.h"
#include "mesh/roi.h"
#include "registration/icp.h"
#include "render/context.h"
#include "scanner/analysis.h"
#include "scanner/metric.h"
#include "tools/command.h"
#include "tools/memory.h"
#include "tools/slicer_module.h"
#include "tools/slicer_parameters.h"
#include "volume/load.h"

#include <CLI/CLI.hpp>

#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace glint::cli {

namespace {

namespace fs = std::filesystem;

struct SlicerCall {
    std::map<std::string, std::string> values;  ///< flagged parameters given, by name
    std::map<std::string, bool> booleans;       ///< boolean parameters, by name (absent: false)
    std::vector<std::string> positional;        ///< index parameters, in index order
    std::string return_file;
    std::string process_address;  ///< accepted, unused (see slicer_module.h)
    bool xml = false;
};

// The parser, from the table: every flag takes its value as text; the table's typed
// parameters are converted (with glint's parsers) in options_from().
SlicerCall parse(int argc, char** argv) {
    SlicerCall call;
    CLI::App app{"glint as a 3D Slicer module (glint --xml prints its description)", "glint"};
    app.add_flag("--xml", call.xml, "Print the Slicer Execution Model description");
    app.add_option("--returnparameterfile", call.return_file,
                   "Write the return parameters (name = value) here");
    app.add_option("--processinformationaddress", call.process_address,
                   "Slicer's shared-library modules only; ignored");
    bool echo = false;
    app.add_flag("--echo", echo, "Accepted for Slicer's conventions; ignored");
    int positional_count = 0;
    for (const SlicerGroup& g : slicer_groups())
        for (const SlicerParameter& p : g.parameters) {
            if (p.index >= 0) ++positional_count;
            if (p.longflag.empty()) continue;
            if (p.tag == "boolean")
                app.add_flag("--" + p.longflag, call.booleans[p.name], p.description);
            else app.add_option("--" + p.longflag, call.values[p.name], p.description);
        }
    app.add_option("ARGS", call.positional, "reference, examined, atlas (the index parameters)")
        ->expected(0, positional_count);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        throw InputError(std::string("Slicer module: ") + e.what() +
                         " (glint --xml describes the parameters)");
    }
    // Only the flags given stay (CLI11 leaves an empty string for the others).
    for (auto it = call.values.begin(); it != call.values.end();)
        it = app.get_option("--" + it->first)->count() == 0 ? call.values.erase(it) : std::next(it);
    if (!call.xml && static_cast<int>(call.positional.size()) != positional_count)
        throw InputError("Slicer module: expected " + std::to_string(positional_count) +
                         " index arguments (reference, examined, atlas), found " +
                         std::to_string(call.positional.size()));
    return call;
}

double number_of(const SlicerCall& c, const std::string& name) {
    const std::string& text = c.values.at(name);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v))
        throw InputError("Slicer module: --" + name + " \"" + text + "\": expected a number");
    return v;
}

int integer_of(const SlicerCall& c, const std::string& name) {
    const double v = number_of(c, name);
    if (v != std::floor(v) || std::fabs(v) > 1e9)
        throw InputError("Slicer module: --" + name + " \"" + c.values.at(name) +
                         "\": expected an integer");
    return static_cast<int>(v);
}

std::vector<double> numbers_of(const SlicerCall& c, const std::string& name) {
    std::vector<double> out;
    SlicerCall one;
    std::string text = c.values.at(name);
    for (std::size_t start = 0;;) {
        const std::size_t comma = text.find(',', start);
        one.values[name] =
            text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        out.push_back(number_of(one, name));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

// Every parameter Slicer passed, into the options glint sweep would build (zero thresholds and
// an "auto" unit keep the library's defaults: Slicer always passes a value).
AnalysisOptions options_from(const SlicerCall& c) {
    AnalysisOptions o;
    auto has = [&](const char* name) { return c.values.count(name) != 0; };
    o.fit.mode = c.booleans.at("register") ? FitMode::Register : FitMode::Identity;
    if (has("loss")) o.fit.registration.loss = parse_loss(c.values.at("loss"));
    if (has("fitRoi") && !c.values.at("fitRoi").empty())
        o.fit.registration.roi = parse_roi(c.values.at("fitRoi"));
    if (has("size")) o.sweep.plan.size = integer_of(c, "size");
    if (has("azimuthStep")) o.sweep.plan.azimuth_step_deg = number_of(c, "azimuthStep");
    if (has("elevations")) o.sweep.plan.elevations_deg = numbers_of(c, "elevations");
    if (has("supersample")) o.sweep.render.supersample = integer_of(c, "supersample");
    if (has("roi") && !c.values.at("roi").empty()) o.sweep.plan.roi = parse_roi(c.values.at("roi"));
    if (has("metric")) o.sweep.metric = parse_metric(c.values.at("metric"));
    if (has("backend")) o.sweep.render.backend = parse_backend(c.values.at("backend"));
    if (has("rule")) o.decision.rule = parse_decision_rule(c.values.at("rule"));
    if (has("thresholdDeg") && number_of(c, "thresholdDeg") != 0.0)
        o.decision.threshold = number_of(c, "thresholdDeg");
    if (has("shapeThreshold") && number_of(c, "shapeThreshold") != 0.0)
        o.decision.shape_threshold = number_of(c, "shapeThreshold");
    if (has("minRegionVertices"))
        o.decision.min_region_vertices =
            static_cast<std::size_t>(integer_of(c, "minRegionVertices"));
    if (has("unit") && c.values.at("unit") != "auto") o.units.unit = c.values.at("unit");
    o.exports.write_views = false;
    o.exports.write_exr = false;
    return o;
}

// Slicer reads the last of each tag it finds on stdout; every line is flushed at once.
class SlicerProgress {
  public:
    SlicerProgress() : start_(std::chrono::steady_clock::now()) {
        std::printf(
            "<filter-start><filter-name>glint sweep</filter-name><filter-comment>loading</filter-comment>"
            "</filter-start>\n");
        std::fflush(stdout);
    }
    void stage(std::string_view name) {
        // note: the stages' shares of the whole are rough (the sweep is most of a run).
        static const std::map<std::string_view, double> at{{"fit", 0.05},    {"distance", 0.2},
                                                           {"sweep", 0.3},   {"decide", 0.9},
                                                           {"export", 0.93}, {"pictures", 0.96}};
        const auto it = at.find(name);
        if (it != at.end()) progress(it->second, name);
    }
    void views(std::size_t done, std::size_t total) {
        if (total > 0)
            progress(0.3 + 0.6 * static_cast<double>(done) / static_cast<double>(total), "sweep");
    }
    void finish() {
        progress(1.0, "done");
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        std::printf(
            "<filter-end><filter-name>glint sweep</filter-name><filter-time>%.2f</filter-time></filter-end>\n",
            s);
        std::fflush(stdout);
    }

  private:
    void progress(double fraction, std::string_view comment) {
        std::printf(
            "<filter-progress>%.4f</filter-progress>\n<filter-comment>%.*s</filter-comment>\n",
            fraction, static_cast<int>(comment.size()), comment.data());
        std::fflush(stdout);
    }
    std::chrono::steady_clock::time_point start_;
};

// The results folder of the run, beside the atlas Slicer asked for; removed once the files
// Slicer reads are moved out of it (or when the run fails).
struct ScratchFolder {
    fs::path path;
    ~ScratchFolder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

std::string return_parameters(const AnalysisResult& r) {
    std::size_t count = 0;
    double largest = 0.0, peak = 0.0, lost = 0.0, gained = 0.0, coverage = 0.0;
    if (!r.decisions.empty()) {
        const auto& regions = r.decisions[0].regions.regions;
        count = regions.size();
        if (!regions.empty()) largest = regions.front().area;  // sorted by area, largest first
        for (const auto& g : regions) {
            if (std::fabs(g.peak_depth) > std::fabs(peak)) peak = g.peak_depth;
            (g.volume < 0 ? lost : gained) += std::fabs(g.volume);
        }
        coverage = 100.0 * r.sweep.zooms[0].coverage.fraction;
    }
    const double rms = r.fit.registration ? r.fit.registration->rms : 0.0;
    char b[640];
    std::snprintf(
        b, sizeof b,
        "regionCount = %zu\nlargestRegionArea = %.9g\npeakDepth = %.9g\nvolumeLost = %.9g\nvolumeGained = "
        "%.9g\ncoverage = %.6g\nfitRotationDeg = %.9g\nfitRms = %.9g\nlengthUnit = %s\n",
        count, largest, peak, lost, gained, coverage,
        rotation_angle_deg(r.fit.reference_from_examined), rms, r.unit.c_str());
    return b;
}

// Moves `name` out of the run's folder to where Slicer reads it (one rename: same folder tree).
void deliver(const fs::path& folder, const char* name, const std::string& to) {
    if (to.empty()) return;
    std::error_code ec;
    fs::rename(folder / name, to, ec);
    if (ec)
        throw IoError("Slicer module: cannot move " + (folder / name).string() + " to " + to +
                      ": " + ec.message());
}

}  // namespace

void run_slicer_module(int argc, char** argv) {
    const SlicerCall call = parse(argc, argv);
    if (call.xml) {
        std::fputs(slicer_xml().c_str(), stdout);
        return;
    }
    AnalysisOptions options = options_from(call);
    const fs::path atlas = call.positional[2];
    ScratchFolder scratch{atlas.parent_path() / (".glint-slicer-" + std::to_string(::getpid()) +
                                                 "-" + atlas.filename().string())};
    options.exports.output = scratch.path;
    options.exports.command_line = global_flags().command_line;
    options.validate();
    SlicerProgress progress;
    const LoadedSurface ref = load_surface(call.positional[0], {});
    LoadedSurface exa = load_surface(call.positional[1], {});
    options.exports.inputs = {
        {"reference", call.positional[0], "", ref.mesh.vertex_count(), ref.mesh.triangle_count()},
        {"examined", call.positional[1], "", exa.mesh.vertex_count(), exa.mesh.triangle_count()}};
    AnalysisObserver observer;
    observer.stage = [&](std::string_view s) {
        give_back_free_memory();
        progress.stage(s);
    };
    observer.views = [&](std::size_t done, std::size_t total) { progress.views(done, total); };
    const AnalysisResult result = analyse(ref.mesh, std::move(exa.mesh), options, observer);
    deliver(result.output, "atlas.vtp", atlas.string());
    if (call.values.count("regions") != 0)
        deliver(result.output, "regions.csv", call.values.at("regions"));
    if (call.values.count("mosaic") != 0)
        deliver(result.output, "mosaic_z0.png", call.values.at("mosaic"));
    if (!call.return_file.empty())
        write_file_atomically(call.return_file, return_parameters(result));
    progress.finish();
    for (const auto& w : result.warnings) std::printf("warning: %s\n", w.c_str());
}

}  // namespace glint::cli
