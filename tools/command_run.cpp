// glint run SCENARIO… and glint eval SCENARIO…|FOLDER: scenarios end to end, and scored.
#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/input_path.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "scenario/run_scenario.h"
#include "scenario/scenario.h"
#include "tools/command.h"
#include "tools/option_flags.h"
#include "tools/progress.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace glint::cli::run_command {
namespace {

namespace fs = std::filesystem;

struct RunArgs {
    std::vector<std::string> scenarios;
    std::string output = "glint-runs";
    std::string data_root;
    bool views = false;
    bool no_pictures = false;
    bool full = false;
    bool print = false;
    bool force = false;
    AnalysisOptions units;  ///< only its units are set (--unit, --allow-scale-mismatch)
};

fs::path data_root_of(const RunArgs& a) {
    if (!a.data_root.empty()) return a.data_root;
    if (const char* env = std::getenv("GLINT_DATA")) return env;
    return {};
}

// Files named on the command line, folders expanded to their *.toml (sorted). In a folder,
// scenarios tagged "full" run only with --full.
std::vector<fs::path> expand(const RunArgs& a, const fs::path& data_root,
                             std::vector<Scenario>& loaded) {
    std::vector<fs::path> files;
    for (const auto& s : a.scenarios) {
        const fs::path p(s);
        std::error_code ec;
        if (reachable_input(p, "scenario \"" + s + "\"") && fs::is_directory(p, ec)) {
            std::vector<fs::path> in_dir;
            // A subfolder this user may not enter is an error naming it, not a scenario less.
            fs::path entered = p;  // the folder the next step lists
            for (auto it = fs::recursive_directory_iterator(p, ec);
                 !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
                std::error_code kind;
                if (it->is_directory(kind)) entered = it->path();
                if (it->is_regular_file(kind) && it->path().extension() == ".toml")
                    in_dir.push_back(it->path());
            }
            if (ec)
                throw IoError("scenario folder \"" + s + "\": cannot list \"" + entered.string() +
                              "\": " + ec.message() + "; expected folders this user may read");
            std::sort(in_dir.begin(), in_dir.end());
            if (in_dir.empty()) throw InputError("folder \"" + s + "\" holds no .toml scenario");
            for (auto& f : in_dir) {
                Scenario sc = load_scenario(f, data_root);
                const bool is_full =
                    std::find(sc.tags.begin(), sc.tags.end(), "full") != sc.tags.end();
                if (is_full && !a.full) continue;
                files.push_back(f);
                loaded.push_back(std::move(sc));
            }
        } else {
            files.push_back(p);
            loaded.push_back(load_scenario(p, data_root));
        }
    }
    return files;
}

std::string opt(const std::optional<double>& v, const char* f = "%.3f") {
    if (!v) return "-";
    char b[32];
    std::snprintf(b, sizeof b, f, *v);
    return b;
}

nlohmann::json outcome_json(const ScenarioOutcome& o) {
    nlohmann::json j = {
        {"scenario", o.name},
        {"file", o.file.string()},
        {"skipped", o.skipped},
        {"skip_reason", o.skip_reason},
        {"passed", o.passed()},
        {"failures", o.failures},
        {"views", o.views},
        {"regions", o.regions},
        {"largest_kind", o.largest_kind},
        {"first_region",
         {{"kind", o.first_kind}, {"area", o.first_area}, {"volume", o.first_volume}}},
        {"coverage", o.coverage},
        {"compared", o.compared},
        {"threshold_deg", o.threshold_deg},
        {"fit", o.fit_mode},
        {"seconds", o.seconds},
        {"output", absolute_output(o.output)}};
    if (o.score)
        j["score"] = {
            {"precision", o.score->precision},
            {"recall", o.score->recall},
            {"f1", o.score->f1},
            {"iou", o.score->iou},
            {"true_positive", o.score->true_positive},
            {"false_positive", o.score->false_positive},
            {"false_negative", o.score->false_negative},
            {"truth_vertices", o.score->truth_vertices},
            {"centroid_error", o.score->centroid_error ? nlohmann::json(*o.score->centroid_error)
                                                       : nlohmann::json()}};
    if (o.pose)
        j["pose_error"] = {{"rotation_deg", o.pose->rotation_deg},
                           {"translation", o.pose->translation},
                           {"scale", o.pose->scale}};
    auto tally_json = [](const RegionTally& t) {
        return nlohmann::json{{"regions", t.regions},
                              {"false_regions", t.false_regions},
                              {"damages", t.damages},
                              {"damages_detected", t.damages_detected},
                              {"close_region_vertices", t.close_region_vertices}};
    };
    if (o.tally) j["tally"] = tally_json(*o.tally);
    if (const auto& a = o.asymmetry) {
        const SymmetryPlane& p = a->plane;
        j["asymmetry"] = {
            {"plausible", a->plausible},
            {"verdict", a->verdict},
            {"plane", to_string(p)},
            {"plane_angle_deg",
             a->plane_angle_deg ? nlohmann::json(*a->plane_angle_deg) : nlohmann::json()},
            {"plane_offset", a->plane_offset ? nlohmann::json(*a->plane_offset) : nlohmann::json()},
            {"findings", a->texts}};
    }
    if (o.baseline)
        j["baseline_distance"] = {{"threshold", o.baseline->threshold},
                                  {"precision", o.baseline->score.precision},
                                  {"recall", o.baseline->score.recall},
                                  {"f1", o.baseline->score.f1},
                                  {"tally", tally_json(o.baseline->tally)}};
    return j;
}

// The first error a scenario threw (bad input, device, I/O), rethrown once every scenario ran
// and the results are written: one line on stderr and that error's exit code.
std::exception_ptr first_error;

std::vector<ScenarioOutcome> run_all(const RunArgs& a, bool score_table) {
    const fs::path root = data_root_of(a);
    std::vector<Scenario> scenarios;
    expand(a, root, scenarios);
    // An input this user may not reach stops the run before anything is written.
    for (const auto& sc : scenarios) (void)missing_input(sc);
    // Earlier results are refused before any scenario runs (not after the first one).
    if (!a.force)
        for (const auto& sc : scenarios)
            if (std::error_code e; fs::exists(fs::path(a.output) / sc.name, e))
                throw InputError("output folder \"" + (fs::path(a.output) / sc.name).string() +
                                 "\" exists (an earlier run of scenario " + sc.name +
                                 "); give --force to replace it");
    // No scenario's folder, nor eval.json / eval.csv, is, holds or lies inside an input.
    for (const auto& sc : scenarios)
        guard_outputs({fs::path(a.output) / sc.name, fs::path(a.output) / "eval.json",
                       fs::path(a.output) / "eval.csv"},
                      {sc.file, sc.reference.mesh, sc.examined.mesh}, OutputParent::MayBeCreated);
    std::error_code ec;
    fs::create_directories(a.output, ec);
    if (ec) throw IoError("output folder \"" + a.output + "\": " + ec.message());
    std::vector<ScenarioOutcome> outcomes;
    for (const auto& sc : scenarios) {
        StageProgress progress(sc.name);
        ScenarioRunOptions options;
        options.output_root = a.output;
        options.write_views = a.views;
        options.write_pictures = !a.no_pictures;
        options.replace_existing = a.force;
        options.unit = a.units.units.unit;
        options.allow_scale_mismatch = a.units.units.allow_scale_mismatch;
        options.command_line = global_flags().command_line;
        progress.listen(options.observer);
        ScenarioOutcome o;
        try {
            o = run_scenario(sc, options);
        } catch (const Error& e) {
            // One broken scenario does not hide the others' results: it is reported, fails,
            // and the first such error decides the exit code (check()).
            o.name = sc.name;
            o.file = sc.file;
            o.failures.push_back(std::string("error: ") + e.what());
            if (!first_error) {
                // Said once: errors of run_scenario may name the scenario already.
                const std::string named = "scenario \"" + sc.file.string() + "\": ";
                const std::string where =
                    std::string_view(e.what()).starts_with(named) ? "" : named;
                if (dynamic_cast<const InputError*>(&e))
                    first_error = std::make_exception_ptr(InputError(where + e.what()));
                else if (dynamic_cast<const DeviceError*>(&e))
                    first_error = std::make_exception_ptr(DeviceError(where + e.what()));
                else first_error = std::make_exception_ptr(IoError(where + e.what()));
            }
        }
        progress.finish();
        print_warnings(o.warnings, o.name);
        if (!global_flags().json && !score_table) {
            if (o.skipped) std::printf("%s: skipped (%s)\n", o.name.c_str(), o.skip_reason.c_str());
            else if (o.asymmetry && !o.asymmetry->plausible)
                std::printf("%s: no asymmetry reported, nothing written, %.1f s%s\n",
                            o.name.c_str(), o.seconds, o.passed() ? "" : " (expectations failed)");
            else
                std::printf("%s: %zu region(s), coverage %.1f%%, %.1f s, atlas in %s%s\n",
                            o.name.c_str(), o.regions, 100 * o.coverage, o.seconds,
                            o.output.string().c_str(), o.passed() ? "" : " (expectations failed)");
            if (o.asymmetry) {
                std::printf("  %s\n", o.asymmetry->verdict.c_str());
                for (const auto& t : o.asymmetry->texts) std::printf("  %s\n", t.c_str());
            }
            for (const auto& f : o.failures) std::printf("  %s\n", f.c_str());
        }
        outcomes.push_back(std::move(o));
    }
    return outcomes;
}

void check(const std::vector<ScenarioOutcome>& outcomes) {
    if (first_error) std::rethrow_exception(first_error);
    std::size_t failed = 0;
    for (const auto& o : outcomes) failed += !o.skipped && !o.passed();
    if (failed)
        throw CheckFailed(std::to_string(failed) + " of " + std::to_string(outcomes.size()) +
                          " scenario(s) did not meet their [expect]");
}

void run_command(const RunArgs& a) {
    if (a.print) {
        // The options each scenario's analysis would run with, loading no mesh.
        std::vector<Scenario> scenarios;
        expand(a, data_root_of(a), scenarios);
        for (const auto& sc : scenarios)
            print_options(sc.analysis, scenario_exports(sc, a.views, !a.no_pictures));
        return;
    }
    const auto outcomes = run_all(a, false);
    if (global_flags().json) {
        nlohmann::json j = nlohmann::json::array();
        for (const auto& o : outcomes) j.push_back(outcome_json(o));
        std::cout << json_text(j, 2) << '\n';
    }
    check(outcomes);
}

void eval_command(const RunArgs& a) {
    const auto outcomes = run_all(a, true);
    nlohmann::json all = nlohmann::json::array();
    std::ostringstream csv;
    csv << "scenario,status,regions,kind,coverage,threshold_deg,precision,recall,f1,iou,centroid_error,"
           "rotation_error_deg,translation_error,seconds,false_regions,damages,damages_detected,close_region_vertices,"
           "baseline_threshold,baseline_f1,baseline_regions,baseline_false_regions,compared\n";
    std::ostringstream table;
    char line[512];
    std::snprintf(
        line, sizeof line,
        "%-34s %-6s %4s %-4s %6s %6s %6s %6s %6s %6s %6s %8s %9s %9s %6s %5s %5s %5s %6s %5s\n",
        "scenario", "status", "reg", "kind", "cover", "cmp", "thr°", "prec", "recall", "F1", "IoU",
        "centroid", "rot°", "transl", "s", "false", "found", "close", "b.F1", "b.reg");
    table << line;
    for (const auto& o : outcomes) {
        all.push_back(outcome_json(o));
        const std::string status = o.skipped ? "skip" : (o.passed() ? "pass" : "FAIL");
        auto s = [&](auto getter) -> std::optional<double> {
            if (!o.score) return std::nullopt;
            return getter(*o.score);
        };
        const auto prec = s([](const DetectionScore& d) { return d.precision; });
        const auto rec = s([](const DetectionScore& d) { return d.recall; });
        const auto f1 = s([](const DetectionScore& d) { return d.f1; });
        const auto iou = s([](const DetectionScore& d) { return d.iou; });
        const std::optional<double> cen = o.score ? o.score->centroid_error : std::nullopt;
        const std::optional<double> rot =
            o.pose ? std::optional<double>(o.pose->rotation_deg) : std::nullopt;
        const std::optional<double> tr =
            o.pose ? std::optional<double>(o.pose->translation) : std::nullopt;
        const auto tally = [&](auto getter) -> std::optional<double> {
            if (!o.tally) return std::nullopt;
            return static_cast<double>(getter(*o.tally));
        };
        const auto false_regions = tally([](const RegionTally& t) { return t.false_regions; });
        const auto close = tally([](const RegionTally& t) { return t.close_region_vertices; });
        const std::string found =
            o.tally && o.tally->damages
                ? std::to_string(o.tally->damages_detected) + "/" + std::to_string(o.tally->damages)
                : "-";
        const std::optional<double> bf1 =
            o.baseline ? std::optional<double>(o.baseline->score.f1) : std::nullopt;
        const std::optional<double> breg =
            o.baseline ? std::optional<double>(static_cast<double>(o.baseline->tally.regions))
                       : std::nullopt;
        std::snprintf(
            line, sizeof line,
            "%-34s %-6s %4zu %-4s %6.3f %6.3f %6.2f %6s %6s %6s %6s %8s %9s %9s %6.1f %5s %5s %5s %6s %5s\n",
            o.name.substr(0, 34).c_str(), status.c_str(), o.regions,
            o.largest_kind.substr(0, 4).c_str(), o.coverage, o.compared, o.threshold_deg,
            opt(prec).c_str(), opt(rec).c_str(), opt(f1).c_str(), opt(iou).c_str(),
            opt(cen, "%.3g").c_str(), opt(rot, "%.5f").c_str(), opt(tr, "%.3g").c_str(), o.seconds,
            opt(false_regions, "%.0f").c_str(), found.c_str(), opt(close, "%.0f").c_str(),
            opt(bf1).c_str(), opt(breg, "%.0f").c_str());
        table << line;
        for (const auto& f : o.failures) table << "    " << f << '\n';
        if (o.skipped) table << "    " << o.skip_reason << '\n';
        csv << o.name << ',' << status << ',' << o.regions << ',' << o.largest_kind << ','
            << o.coverage << ',' << o.threshold_deg << ',' << opt(prec, "%.6f") << ','
            << opt(rec, "%.6f") << ',' << opt(f1, "%.6f") << ',' << opt(iou, "%.6f") << ','
            << opt(cen, "%.6g") << ',' << opt(rot, "%.6g") << ',' << opt(tr, "%.6g") << ','
            << o.seconds << ',' << opt(false_regions, "%.0f") << ','
            << (o.tally ? std::to_string(o.tally->damages) : "-") << ','
            << (o.tally ? std::to_string(o.tally->damages_detected) : "-") << ','
            << opt(close, "%.0f") << ','
            << (o.baseline ? std::to_string(o.baseline->threshold) : "-") << ',' << opt(bf1, "%.6f")
            << ',' << opt(breg, "%.0f") << ','
            << (o.baseline ? std::to_string(o.baseline->tally.false_regions) : "-") << ','
            << o.compared << '\n';
    }
    write_file_atomically(fs::path(a.output) / "eval.json", json_text(all, 2) + "\n");
    write_file_atomically(fs::path(a.output) / "eval.csv", csv.str());
    if (global_flags().json) std::cout << json_text(all, 2) << '\n';
    else std::cout << table.str() << "eval.json and eval.csv in " << a.output << '\n';
    check(outcomes);
}

void add_common(CLI::App* cmd, RunArgs& a) {
    cmd->add_option("SCENARIO", a.scenarios, "Scenario files (.toml) or folders of them")
        ->required();
    cmd->add_option("-o,--output", a.output, "Folder for the atlases (one sub-folder per scenario)")
        ->capture_default_str();
    cmd->add_option("--data-root", a.data_root,
                    "Where scenario mesh paths not found beside the scenario are looked up "
                    "(default: $GLINT_DATA)");
    cmd->add_flag("--views", a.views, "Also write what each view measured (PNG + EXR)");
    cmd->add_flag("--no-pictures", a.no_pictures,
                  "Draw no PNG picture (atlas files, report.json and report.html stay; the image "
                  "library is never loaded)");
    cmd->add_flag("--full", a.full,
                  "Folders: include scenarios tagged 'full' (longer than the CI suite)");
    cmd->add_flag(
        "--force", a.force,
        "Replace existing atlas folders of these scenarios (each once its run completes)");
    add_analysis_flags(*cmd, a.units, kUnitGroup);
}

void setup(CLI::App& app) {
    static RunArgs run_args;
    static RunArgs eval_args;
    auto* run = app.add_subcommand("run", "Run scenarios end to end (fit, sweep, atlas)");
    add_common(run, run_args);
    add_print_options_flag(*run, run_args.print);
    run->callback([] { run_command(run_args); });
    auto* eval = app.add_subcommand("eval",
                                    "Run scenarios and score them against their ground truth; "
                                    "exit 1 when an [expect] fails");
    add_common(eval, eval_args);
    eval->callback([] { eval_command(eval_args); });
}

const CommandRegistrar registrar(70, setup);

}  // namespace
}  // namespace glint::cli::run_command
