// Exports of an analysis into its output folder (DESIGN.md "Outputs a user opens"):
//   atlas.ply / .vtk / .vtp  reference surface coloured by damage, with per-vertex scalars in
//                          the forms MeshLab, CloudCompare, ParaView and 3D Slicer read (mesh/write.h)
//   regions.csv            one row per region and zoom
//   report.json            inputs with SHA-256, device, backend, options, fit, floors and
//                          rule, coverage, unseen patches, regions, histograms, views, timings
//   atlas.png, mosaic_z<k>.png, views/*.png   the pictures (scanner/pictures.h)
//   report.html            the page to open in a browser (scanner/report_html.h)
// (views/*.exr are written while the sweep runs: scanner/view_exports.h.)
#pragma once

#include "mesh/mesh.h"
#include "scanner/analysis.h"
#include "scanner/output_folder.h"

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace glint {

/// SHA-256 of a file as lowercase hex. \throw IoError.
[[nodiscard]] std::string sha256_file(const std::filesystem::path& path);

/// The reference with the atlas scalars: per zoom k "<metric>_max_z<k>", "<metric>_mean_z<k>",
/// "depth_z<k>", "missing_z<k>", "count_z<k>", "seen_z<k>", "region_z<k>", and "distance";
/// colours: the signed distance on the pictures' diverging map and range (shape_scale in
/// scanner/pictures.h), grey where zoom 0 saw nothing.
[[nodiscard]] Mesh make_atlas_mesh(const Mesh& reference, const AnalysisResult& result);

/// The atlas scalar MeshLab shows as `quality`: the metric's per-vertex mean at zoom 0 (the
/// normal evidence the decision uses), e.g. "angle_mean_z0".
[[nodiscard]] std::string atlas_quality_scalar(const AnalysisResult& result);

/// The report as JSON text (what report.json holds).
[[nodiscard]] std::string report_json(const Mesh& reference, const AnalysisResult& result,
                                      const AnalysisOptions& options);

/// regions.csv as text.
[[nodiscard]] std::string regions_csv(const AnalysisResult& result);

/// Writes atlas.ply, atlas.vtk, atlas.vtp, regions.csv, report.json, the pictures and
/// report.html into the folder. `stage` (when set) is called with "pictures" before the
/// pictures are drawn, after the other files (AnalysisObserver::stage).
void write_outputs(const OutputFolder& folder, const Mesh& reference, const AnalysisResult& result,
                   const AnalysisOptions& options,
                   const std::function<void(std::string_view stage)>& stage = {});

}  // namespace glint
