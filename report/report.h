// Exports of an analysis into its output folder (DESIGN.md "Outputs a user opens"):
//   atlas.ply / .vtk / .vtp  reference surface coloured by damage, with the per-vertex fields of
//                          report/atlas_fields.h in the forms MeshLab, CloudCompare, ParaView and
//                          3D Slicer read (mesh/write.h)
//   regions.csv            one row per region and zoom
//   report.json            inputs with SHA-256, device, backend, options, fit, floors and
//                          rule, coverage, unseen patches, regions, histograms, views, timings
//   atlas.png, mosaic_z<k>.png, views/*.png   the pictures (report/pictures.h)
//   report.html            the page to open in a browser (report/report_html.h)
// (views/*.exr are written while the sweep runs: report/view_exports.h.)
#pragma once

#include "analysis/analysis.h"
#include "mesh/checksum.h"
#include "mesh/mesh.h"
#include "report/atlas_fields.h"
#include "report/export_options.h"
#include "report/inspect.h"
#include "report/output_folder.h"
#include "report/report_html.h"
#include "report/run_inputs.h"
#include "report/view_measurements.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace glint {

/// Why a "missing surface" region has no depth or volume (report.json's depth_note; its
/// peak_depth, mean_depth and volume are null): the examined scan holds no surface there.
inline constexpr std::string_view kMissingSurfaceNote =
    "no examined surface there: no depth or volume to measure";

/// What a dent's depth means where it is a hole (report.json's depth_note): the examined
/// surface holds nothing inside the hole, so the depth is what the reference stood above the
/// hole's rim, a lower bound of the loss (decision/comparison.h).
inline constexpr std::string_view kHoleLossNote =
    "surface gone in a hole: the depth is how far the reference stood above the hole's rim, a "
    "lower bound of the loss";

/// The report as JSON text (what report.json holds): the inputs of `record` with their
/// SHA-256 (a mesh file's from the bytes its loader read, any other file read once more), the options, the results.
/// `mirror`: the examined surface is the reference's mirror image (glint asymmetry): the
/// regions' findings say "more" or "less than the mirrored other side".
[[nodiscard]] std::string report_json(const Mesh& reference, const AnalysisResult& result,
                                      const InspectOptions& options, const RunRecord& record,
                                      bool mirror = false);

/// regions.csv as text.
[[nodiscard]] std::string regions_csv(const AnalysisResult& result);

/// Writes atlas.ply, atlas.vtk, atlas.vtp (those ExportOptions::atlas_files names), regions.csv,
/// report.json (`report_json`'s text), the pictures and report.html into the folder; the page's
/// live view gets `examined` (null: the page says it has none). `observer` hears the stages in
/// their order: "atlas files" (items: each of the atlas files, regions.csv and report.json),
/// "report page" (waiting for the page's data), "pictures" (items: each per-view picture; also
/// where the caller may hand back memory), "mosaics" (items: each zoom), "atlas.png",
/// "report.html". `measured`: what each view measured, for the pictures (write_pictures).
/// Returns the atlas mesh when ExportOptions::keep_atlas.
std::optional<Mesh> write_outputs(const OutputFolder& folder, const Mesh& reference,
                                  const AnalysisResult& result, const LiveSurface* examined,
                                  const ExportOptions& exports, const RunRecord& record,
                                  const std::string& report_json,
                                  const AnalysisObserver& observer = {},
                                  const ViewMeasurements* measured = nullptr);

}  // namespace glint
