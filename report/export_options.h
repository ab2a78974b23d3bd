// What a run with outputs writes (report/inspect.h): the output folder and which files go in it.
#pragma once

#include "analysis/analysis.h"
#include "analysis/option_registry.h"
#include "report/mirror_pictures.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

/// Which atlas files a run writes: atlas.ply (MeshLab, CloudCompare, Open3D, Blender) and
/// atlas.vtp (VTK XML: ParaView, 3D Slicer, VTK) by default; atlas.vtk (legacy ASCII: the
/// same programs read it) only when asked. On a 2M-triangle mesh they are 129, 126 and 212 MB;
/// the legacy file was the largest and slowest to write and opens in no program the other
/// two miss, so it is one flag away (--atlas-formats ply,vtk,vtp).
struct AtlasFiles {
    bool ply = true;
    bool vtk = false;
    bool vtp = true;
    [[nodiscard]] bool operator==(const AtlasFiles&) const = default;
};

/// "ply,vtp" → those files. \throw OptionError naming `key` for an unknown or repeated name or
/// an empty list.
[[nodiscard]] AtlasFiles parse_atlas_files(std::string_view list, const std::string& key);

/// "ply,vtk,vtp": the names of the files written, in that order.
[[nodiscard]] std::string to_string(const AtlasFiles& files);

struct ExportOptions {
    /// The output folder (written complete or not at all, report/output_folder.h); empty:
    /// nothing is written.
    std::filesystem::path output;
    /// PNG pictures: per-view pictures, mosaics, atlas.png and the pictures report.html shows.
    /// false: none is drawn and the image library is never loaded (scripts and cohorts that read
    /// report.json and the atlas files); the atlas files keep their colours.
    bool write_pictures = true;
    /// Per-view PNGs of what each view measured (with write_pictures). Off by default: the
    /// mosaic charts every view and draws the regions' best ones whole, report.html shows
    /// those; drawing all of them again cost a third of a 200k-triangle run.
    bool write_views = false;
    /// Per-view EXR with the raw numbers (opt-in: a GPU sweep then reads every frame back).
    bool write_exr = false;
    AtlasFiles atlas_files;  ///< atlas.ply / atlas.vtk / atlas.vtp
    /// An existing output folder is replaced (atomically, when the run completes); false:
    /// it is refused before anything is loaded (--force).
    bool replace_existing = false;
    /// Size of the views the mosaic draws whole (the regions' best views, the views that
    /// measured most), pixels.
    int mosaic_tile = 256;
    /// Which axis the pictures draw up ("+x" … "-z", report/orientation.h); empty: superior
    /// when the reference is in a patient space, else +z.
    std::string up;
    /// Per-vertex scalars added to the atlas files after glint's own fields (e.g. a scenario's
    /// ground truth, "truth_damage_id" and "truth_distance{unit}", to be seen beside them
    /// in a viewer); each holds one value per reference vertex. A name ending in "{unit}" gets
    /// the run's unit there ("_mm", mesh/units.h unit_suffix); NaN is written as 0.
    std::vector<std::pair<std::string, std::vector<float>>> extra_scalars;
    /// Keep the atlas mesh (the reference with every atlas field) in the result (Python's
    /// Analysis.atlas); otherwise it lives only while its files are written.
    bool keep_atlas = false;
    /// The examined surface is the reference's mirror image (glint asymmetry): the pictures
    /// draw this plane and speak of the sides (report/mirror_pictures.h); not an option.
    std::optional<MirrorPictures> mirror;

    /// \throw OptionError; InputError when the output folder exists and may not be replaced.
    void validate() const;
};

/// The export options of the command line, Python and the JSON (analysis/option_registry.h;
/// scenario files do not set them).
[[nodiscard]] const std::vector<OptionField<ExportOptions>>& export_option_table();

/// The options as JSON text (report.json's "analysis", --print-options; two callers that mean
/// the same run produce the same text).
[[nodiscard]] std::string to_json(const AnalysisOptions& options, const ExportOptions& exports);

}  // namespace glint
