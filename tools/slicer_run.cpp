// A Slicer call: parse the flags and index arguments of the description, run the sweep,
// put atlas / regions / mosaic where Slicer asked, write the return parameters, and report
// progress on stdout (tools/slicer_module.h).
#include "analysis/analysis.h"
#include "analysis/option_registry.h"
#include "mesh/atomic_file.h"
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/geometry.h"
#include "mesh/json_text.h"
#include "mesh/parse.h"
#include "mesh/roi.h"
#include "registration/icp.h"
#include "render/context.h"
#include "report/inspect.h"
#include "report/run_inputs.h"
#include "scanner/metric.h"
#include "tools/command.h"
#include "tools/memory.h"
#include "tools/option_flags.h"
#include "tools/slicer_markups.h"
#include "tools/slicer_module.h"
#include "tools/slicer_parameters.h"
#include "volume/load.h"
#include "volume/volume.h"

#include <nlohmann/json.hpp>

#include <CLI/CLI.hpp>

#include <unistd.h>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
    bool print_options = false;  ///< glint's own: the resolved options as JSON, nothing run
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
    app.add_flag("--print-options", call.print_options,
                 "Print the options the call resolves to as JSON and stop (scripts, tests)");
    int positional_count = 0;
    for (const SlicerGroup& g : slicer_groups())
        for (const SlicerParameter& p : g.parameters) {
            if (p.index >= 0) ++positional_count;
            if (p.longflag.empty()) continue;
            if (p.tag == "boolean")
                app.add_flag("--" + p.longflag, call.booleans[p.name], p.description);
            else app.add_option("--" + p.longflag, call.values[p.name], p.description);
        }
    // note: glint's calls before the inputs became flags passed reference, examined, atlas as
    // arguments; that form is still read (scripts), Slicer's is the atlas alone.
    app.add_option("ARGS", call.positional,
                   "atlas (the index parameter), or reference, examined, atlas")
        ->expected(0, positional_count + 2);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        throw InputError(std::string("Slicer module: ") + e.what() +
                         " (glint --xml describes the parameters)");
    }
    // Only the flags given stay (CLI11 leaves an empty string for the others).
    for (auto it = call.values.begin(); it != call.values.end();)
        it = app.get_option("--" + it->first)->count() == 0 ? call.values.erase(it) : std::next(it);
    if (!call.xml && call.positional.size() != 1 && call.positional.size() != 3)
        throw InputError(
            "Slicer module: expected the atlas path as the last argument (or "
            "reference, examined, atlas), found " +
            std::to_string(call.positional.size()) + " arguments");
    return call;
}

// Every parameter Slicer passed, through the option registry, into the options glint sweep
// would build. Slicer always passes a value: an optional number at 0 and the unit "auto" keep
// the library's defaults, and a boolean is passed only when true (an on-by-default flag is its
// negation, "noCoarse"; tools/slicer_module.cpp).
InspectOptions options_from(const SlicerCall& c) {
    InspectOptions io;
    AnalysisOptions& o = io.analysis;
    o.fit.mode = c.booleans.at("register") ? FitMode::Register : FitMode::Identity;
    const AnalysisOptions defaults;
    for (const auto& f : analysis_option_table()) {
        const std::string name(f.info.slicer);
        try {
            if (f.info.kind == OptionKind::Flag) {
                const bool on_by_default = std::get<bool>(f.get(defaults));
                const std::string passed =
                    on_by_default ? "no" +
                                        std::string(1, static_cast<char>(std::toupper(
                                                           static_cast<unsigned char>(name[0])))) +
                                        name.substr(1)
                                  : name;
                const auto it = c.booleans.find(passed);
                if (it != c.booleans.end() && it->second) set_option(o, f, !on_by_default);
                continue;
            }
            const auto it = c.values.find(name);
            if (it == c.values.end()) continue;
            std::string text = it->second;
            if (f.info.kind == OptionKind::OptionalNumber &&
                std::strtod(text.c_str(), nullptr) == 0.0)
                text.clear();
            if (f.info.kind == OptionKind::Choice && f.info.may_be_unset && text == "auto")
                text.clear();
            if (f.info.kind == OptionKind::Region && is_slicer_region(text))
                text = to_string(parse_slicer_region(text));
            set_option(o, f, parse_option_text(f.info, text));
        } catch (const OptionError& e) {
            throw InputError("Slicer module: " + e.named("--" + name));
        } catch (const InputError& e) {
            throw InputError("Slicer module: --" + name + ": " + e.what());
        }
    }
    // Slicer writes its models in millimetres (LPS): what a file stating its unit would say.
    if (o.units.unit.empty()) o.units.unit = "mm";
    io.exports.write_views = false;
    io.exports.write_exr = false;
    return io;
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

// The results folder of the run and the landmarks file made from markups, beside the atlas
// Slicer asked for; removed once the files Slicer reads are moved out (or when the run fails).
struct ScratchFolder {
    fs::path path;
    fs::path landmarks() const { return path.string() + ".landmarks.json"; }
    ~ScratchFolder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
        fs::remove(landmarks(), ignored);
    }
};

// One surface of the call: a model or a volume, from the flags (Slicer) or the arguments.
struct SurfaceInput {
    std::string role;
    fs::path path;
    bool is_volume = false;
};

SurfaceInput surface_input(const SlicerCall& c, const std::string& role, std::size_t argument) {
    const std::string model = role + "Model", volume = role + "Volume";
    const bool has_model = c.values.count(model) != 0, has_volume = c.values.count(volume) != 0;
    if (c.positional.size() == 3) {
        if (has_model || has_volume)
            throw InputError("Slicer module: the " + role + " is given as an argument and as --" +
                             (has_model ? model : volume) + ", expected one");
        const fs::path path = c.positional[argument];
        return {role, path, is_volume_path(path)};
    }
    if (has_model == has_volume)
        throw InputError(
            "Slicer module: " +
            (has_model ? "both --" + model + " and --" + volume + " given" : "no " + role) +
            ", expected one of --" + model + " (a model) or --" + volume + " (a volume)");
    const fs::path path = c.values.at(has_model ? model : volume);
    if (has_volume && !is_volume_path(path))
        throw InputError("Slicer module: --" + volume + " \"" + path.string() +
                         "\" is no volume file, expected .nrrd, .nii, .nii.gz, .mha or .mhd");
    return {role, path, is_volume_path(path)};
}

// Slicer writes models and volumes in LPS; a mesh that states RAS (SPACE=RAS) is turned into
// LPS (x and y negated: a half turn about z, so the winding stays) so that the ROIs, the
// landmarks and the atlas Slicer reads back share one space.
void into_lps(RunInput& input) {
    if (input.record.space != "RAS") return;
    for (auto& p : input.mesh.positions) p = Vec3f(-p.x(), -p.y(), p.z());
    for (auto& n : input.mesh.normals) n = Vec3f(-n.x(), -n.y(), n.z());
    input.record.space = "LPS";
    input.warnings.push_back(input.record.path.string() +
                             ": states SPACE=RAS, turned into LPS (Slicer's space)");
}

RunInput load_surface_input(const SurfaceInput& in, const SlicerCall& c) {
    SurfaceOptions surface;
    if (in.is_volume) {
        const auto iso = c.values.find("iso");
        if (iso != c.values.end()) {
            const auto v = parse_number_list(iso->second, "Slicer module: --iso");
            if (v.size() != 1)
                throw InputError("Slicer module: --iso \"" + iso->second +
                                 "\": expected one number (the surface's value)");
            surface.iso = v[0];
        }
        surface.largest = c.booleans.at("largest");
        const auto seed = c.values.find("seed");
        if (seed != c.values.end()) {
            if (surface.largest)
                throw InputError(
                    "Slicer module: --largest and --seed both given, expected one "
                    "(the largest part of the surface, or the part nearest the seed)");
            const auto v = parse_number_list(seed->second, "Slicer module: --seed");
            if (v.size() != 3)
                throw InputError("Slicer module: --seed \"" + seed->second +
                                 "\": expected x,y,z (a point, mm)");
            surface.seed = Vec3d(v[0], v[1], v[2]);
        }
    }
    RunInput loaded = load_run_input(in.role, in.path, surface);
    into_lps(loaded);
    return loaded;
}

// The two landmark point lists (markups, paired in order) as a landmarks file
// (registration/landmarks.h): the registration starts from their fit.
void landmarks_from_markups(const SlicerCall& c, FitOptions& fit, const fs::path& file) {
    const bool has_reference = c.values.count("referenceLandmarks") != 0;
    const bool has_examined = c.values.count("examinedLandmarks") != 0;
    if (!has_reference && !has_examined) return;
    if (has_reference != has_examined)
        throw InputError(std::string("Slicer module: --") +
                         (has_reference ? "referenceLandmarks" : "examinedLandmarks") +
                         " given alone, expected both landmark lists (paired in order)");
    if (!fit.landmarks_file.empty())
        throw InputError("Slicer module: landmarks given as markups and as --landmarks \"" +
                         fit.landmarks_file.string() + "\", expected one");
    const auto reference = read_markups_points(c.values.at("referenceLandmarks"));
    const auto examined = read_markups_points(c.values.at("examinedLandmarks"));
    if (reference.size() != examined.size())
        throw InputError("Slicer module: " + std::to_string(reference.size()) +
                         " reference landmarks and " + std::to_string(examined.size()) +
                         " examined landmarks, expected as many of each (paired in order)");
    nlohmann::json pairs = nlohmann::json::array();
    for (std::size_t i = 0; i < reference.size(); ++i)
        pairs.push_back({{"examined", {examined[i].x(), examined[i].y(), examined[i].z()}},
                         {"reference", {reference[i].x(), reference[i].y(), reference[i].z()}}});
    write_file_atomically(file, json_text(nlohmann::json{{"pairs", pairs}}, 1));
    fit.landmarks_file = file;
}

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
    InspectOptions options = options_from(call);
    if (call.print_options) {
        options.validate();
        print_options(options.analysis, options.exports);
        return;
    }
    const fs::path atlas = call.positional.back();
    const SurfaceInput ref_in = surface_input(call, "reference", 0);
    const SurfaceInput exa_in = surface_input(call, "examined", 1);
    ScratchFolder scratch{atlas.parent_path() / (".glint-slicer-" + std::to_string(::getpid()) +
                                                 "-" + atlas.filename().string())};
    options.exports.output = scratch.path;
    landmarks_from_markups(call, options.analysis.fit, scratch.landmarks());
    options.validate();
    SlicerProgress progress;
    const RunInput ref = load_surface_input(ref_in, call);
    RunInput exa = load_surface_input(exa_in, call);
    RunRecord record{.command_line = global_flags().command_line};
    record.add(ref);
    record.add(exa);
    for (const std::string side : {"reference", "examined"})
        if (call.values.count(side + "Landmarks") != 0)
            record.add_file("landmarks", call.values.at(side + "Landmarks"),
                            "markups point list, the " + side + " side of the landmark pairs");
    AnalysisObserver observer;
    observer.stage = [&](std::string_view s) {
        give_back_free_memory();
        progress.stage(s);
    };
    observer.views = [&](std::size_t done, std::size_t total) { progress.views(done, total); };
    const Inspection result = inspect(ref.mesh, std::move(exa.mesh), options, record, observer);
    deliver(result.output, "atlas.vtp", atlas.string());
    for (const auto& [parameter, file] :
         {std::pair{"regions", "regions.csv"}, std::pair{"mosaic", "mosaic_z0.png"},
          std::pair{"atlasPicture", "atlas.png"}, std::pair{"report", "report.html"}})
        if (call.values.count(parameter) != 0)
            deliver(result.output, file, call.values.at(parameter));
    if (!call.return_file.empty())
        write_file_atomically(call.return_file, return_parameters(result.analysis));
    progress.finish();
    for (const auto& w : result.analysis.warnings) std::printf("warning: %s\n", w.c_str());
}

}  // namespace glint::cli
