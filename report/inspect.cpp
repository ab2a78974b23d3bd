#include "report/inspect.h"

#include "analysis/asymmetry.h"
#include "image/image_ops.h"
#include "mesh/atomic_file.h"
#include "mesh/cancel.h"
#include "mesh/fault_injection.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "mesh/stopwatch.h"
#include "report/output_folder.h"
#include "report/report.h"
#include "report/report_html.h"
#include "report/view_exports.h"
#include "report/view_measurements.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <optional>
#include <utility>

namespace glint {

namespace {

using Clock = std::chrono::steady_clock;

// Per-view EXRs hold every pixel's comparison, so those sweeps read their frames back; the
// report says why the comparison left the GPU.
AnalysisOptions analysis_for(const InspectOptions& options, bool writes_exr) {
    AnalysisOptions a = options.analysis;
    if (writes_exr && a.sweep.accumulate == Accumulation::Auto)
        a.sweep.accumulate = Accumulation::Host;
    return a;
}

void note_accumulation(const InspectOptions& options, const AnalysisOptions& used, bool writes_exr,
                       AnalysisResult& result) {
    if (writes_exr && result.sweep.on_gpu)
        result.warnings.push_back(
            "per-view EXRs not written: the sweep compared on the GPU (accumulate = gpu) and "
            "no pixel came back; accumulate = auto or host writes them");
    if (used.sweep.accumulate != options.analysis.sweep.accumulate &&
        result.sweep.renderer.backend == Backend::Vulkan)
        result.sweep.accumulation_note =
            "per-view EXRs hold every pixel's comparison: frames read back (without "
            "--exr compare stays on the GPU)";
}

void add_to_outputs(ReportAddition addition, ExportOptions& exports, std::string& report) {
    for (auto& s : addition.scalars) exports.extra_scalars.push_back(std::move(s));
    if (addition.key.empty()) return;
    nlohmann::json j = nlohmann::json::parse(report);
    j[addition.key] = nlohmann::json::parse(addition.json);
    report = json_text(j, 2) + "\n";  // as report_json writes it
}

}  // namespace

void InspectOptions::validate() const {
    analysis.validate();
    exports.validate();
}

Inspection inspect(const Mesh& reference, Mesh examined, const InspectOptions& options,
                   const RunRecord& record, const AnalysisObserver& observer) {
    const auto t_start = Clock::now();
    options.validate();
    // The output location is checked (and its staging folder made) before the long work.
    std::optional<OutputFolder> folder;
    // Files the options name are inputs before they are read (a mask is read during the fit or
    // the sweep): the output folder below refuses to be, hold or lie inside one (issue 52).
    for (const std::optional<Roi>* roi :
         {&options.analysis.fit.registration.roi, &options.analysis.sweep.plan.roi})
        if (*roi && (*roi)->shape == Roi::Shape::VertexMask) protect_input((*roi)->mask_file);
    if (!options.exports.output.empty()) {
        folder.emplace(options.exports.output, options.exports.replace_existing);
        // A missing image plugin stops the run now, not after the sweep; a run that draws no
        // picture and writes no EXR never loads it.
        if (options.exports.write_pictures || options.exports.write_exr) preload_image_io();
    }
    const bool writes_exr = folder && options.exports.write_exr;
    const AnalysisOptions used = analysis_for(options, writes_exr);

    std::optional<ViewExporter> exporter;
    if (writes_exr) exporter.emplace(*folder, used.sweep.metric, options.exports);
    // What each view measured, kept compactly for its pictures (report/view_measurements.h).
    std::optional<ViewMeasurements> measured;
    AnalysisObserver observed = observer;
    observed.plan = [&](const SweepPlan& plan) {
        if (folder && options.exports.write_pictures) measured.emplace(plan);
        if (observer.plan) observer.plan(plan);
    };
    observed.view = [&](const PlannedView& v, const DeviationMap& d) {
        if (exporter && d.width > 0) exporter->add(v, d);
        if (measured) measured->add(v, d);
        if (observer.view) observer.view(v, d);
    };
    // The page's live view keeps the fitted examined surface, decimated (report/report_html.h),
    // made before analyse() releases the whole one.
    std::optional<LiveSurface> live;
    observed.fitted = [&](const Mesh& fitted, const AnalysisResult& result) {
        if (folder) live = live_examined(fitted, reference, result);
        if (observer.fitted) observer.fitted(fitted, result);
    };
    Inspection out;
    out.analysis = analyse(reference, std::move(examined), used, observed);
    note_accumulation(options, used, writes_exr, out.analysis);
    if (folder && options.exports.write_pictures && out.analysis.sweep.on_gpu)
        out.analysis.warnings.push_back(
            "per-view pictures and mosaic tiles show the atlas from each view: the sweep "
            "compared on the GPU and no per-view pixel came back (accumulate = host draws what "
            "each view measured)");
    auto& warnings = out.analysis.warnings;
    warnings.insert(warnings.begin(), record.warnings.begin(), record.warnings.end());

    fault_point("export");
    throw_if_cancelled();
    if (observer.stage) observer.stage("export");
    const auto t = Clock::now();
    out.analysis.total_seconds = seconds_since(t_start);
    // The addition reads the analysis as it came; a mirror comparison's outputs then give
    // this side against the mirrored other side, report.json's regions included.
    std::optional<ReportAddition> addition;
    if (options.addition) addition = options.addition(out.analysis);
    ExportOptions exports = options.exports;
    if (addition && addition->mirror) {
        as_side_against_mirror(out.analysis);
        exports.mirror = addition->mirror;
    }
    out.report_json = report_json(reference, out.analysis, options, record,
                                  addition && addition->mirror.has_value());
    if (addition) add_to_outputs(std::move(*addition), exports, out.report_json);
    if (folder) {
        try {
            out.atlas =
                write_outputs(*folder, reference, out.analysis, live ? &*live : nullptr, exports,
                              record, out.report_json, observer, measured ? &*measured : nullptr);
        } catch (const IoError& e) {  // the folder the user named, not the staging folder
            throw naming_target(e, folder->staging(), folder->target());
        }
        folder->commit();
        out.output = folder->target();
    } else if (options.exports.keep_atlas) {
        out.atlas = make_atlas_mesh(reference, out.analysis);
    }
    // The reference's BVH served the pictures; a caller that keeps the result (Python) does
    // not keep it too.
    out.analysis.reference_index.reset();
    out.export_seconds = seconds_since(t);
    out.total_seconds = seconds_since(t_start);
    return out;
}

}  // namespace glint
