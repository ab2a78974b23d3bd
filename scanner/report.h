// Exports of a sweep into an output folder (DESIGN.md "Outputs a user opens"):
//   atlas.ply / atlas.vtk  reference surface coloured by damage, with per-vertex scalars
//   regions.csv            one row per region and zoom
//   report.json            inputs with SHA-256, device, backend, plan, fit, thresholds,
//                          coverage, unseen patches, regions, histograms, views, timings
// (views/ and mosaic_z<k>.png are written while the sweep runs, see SweepExporter.)
#pragma once

#include "mesh/mesh.h"
#include "scanner/output_folder.h"
#include "scanner/sweep.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace glint {

/// One input file of a run.
struct InputRecord {
    std::string role;               ///< "reference", "examined", "fit", "scenario"
    std::filesystem::path path;     ///< empty for a generated mesh
    std::string description;        ///< e.g. "phantom condyle ico 5"
    std::size_t vertices = 0;
    std::size_t triangles = 0;
};

/// Context a report needs beyond the sweep itself.
struct ReportContext {
    std::vector<InputRecord> inputs;
    std::string fit_json;                     ///< registration result as JSON text ("" = none)
    std::string command_line;
    std::vector<std::string> warnings;
    std::vector<float> distance;              ///< per reference vertex signed distance (neg = loss), optional
};

/// SHA-256 of a file as lowercase hex. \throw IoError.
[[nodiscard]] std::string sha256_file(const std::filesystem::path& path);

/// Adds the atlas scalars to a copy of the reference: per zoom k "angle_max_z<k>",
/// "angle_mean_z<k>", "depth_z<k>", "count_z<k>", "seen_z<k>", "region_z<k>", plus
/// "distance" when given; colours from zoom 0's mean angle (inferno, 0…2×threshold, unseen grey).
[[nodiscard]] Mesh make_atlas_mesh(const Mesh& reference, const SweepResult& result,
                                   const ReportContext& context);

/// The report as JSON text (what report.json holds).
[[nodiscard]] std::string sweep_report_json(const Mesh& reference, const SweepResult& result,
                                            const ReportContext& context);

/// Writes atlas.ply, atlas.vtk, regions.csv and report.json into the folder.
void write_sweep_outputs(const OutputFolder& folder, const Mesh& reference, const SweepResult& result,
                         const ReportContext& context);

/// Observer for run_sweep writing per-view heat maps (views/z<k>_az<…>_el<…>.png with a
/// colour bar, and .exr with raw angle/depth/silhouette) and one mosaic per zoom.
class SweepExporter {
public:
    struct Options {
        bool write_views = true;      ///< PNG heat maps per view
        bool write_exr = true;        ///< EXR with the raw numbers per view
        double color_max_deg = 20.0;  ///< heat map range 0…color_max_deg
        int mosaic_tile = 128;
    };
    SweepExporter(const OutputFolder& folder, const SweepPlan& plan, Options options);
    ~SweepExporter();
    /// The observer to pass to run_sweep.
    [[nodiscard]] ViewObserver observer();
    /// Writes the mosaics (call after the sweep).
    void finish();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace glint
