#include "report/export_options.h"

#include "analysis/option_fields.h"
#include "mesh/error.h"
#include "mesh/front_end.h"
#include "report/orientation.h"

#include <filesystem>
#include <system_error>

namespace glint {

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
    (void)resolve_orientation(PatientSpace::Unknown, up);
    std::error_code ec;
    if (!output.empty() && !replace_existing && std::filesystem::exists(output, ec))
        throw InputError("output folder \"" + output.string() + "\" exists; give " +
                         spell_flag("force") +
                         " to replace it (the new "
                         "results replace it only when the run completes)");
}

const std::vector<OptionField<ExportOptions>>& export_option_table() {
    using F = OptionFields<ExportOptions>;
    static const std::vector<OptionField<ExportOptions>> table = {
        F::flag(
            {.name = "pictures",
             .section = "exports",
             .key = "pictures",
             .slicer = "pictures",
             .group = kExportGroup,
             .label = "Pictures",
             .help = "PNG pictures: per-view, mosaics, atlas.png, and those report.html shows "
                     "(--no-pictures draws none and never loads the image library; the atlas "
                     "files, report.json and report.html's 3D view stay)"},
            [](auto& o) -> auto& { return o.write_pictures; }),
        F::flag(
            {.name = "views",
             .section = "exports",
             .key = "views",
             .slicer = "views",
             .group = kExportGroup,
             .label = "Per-view pictures",
             .help = "A PNG picture of every view in views/ (without it, the mosaic charts "
                     "every view and draws the regions' best views whole, as report.html does)"},
            [](auto& o) -> auto& { return o.write_views; }),
        F::flag(
            {.name = "exr",
             .section = "exports",
             .key = "exr",
             .slicer = "exr",
             .group = kExportGroup,
             .label = "Per-view EXR",
             .help = "Also per-view EXR files with every pixel's comparison (a GPU sweep then "
                     "reads its frames back)"},
            [](auto& o) -> auto& { return o.write_exr; }),
        F::text(
            {.name = "atlas_formats",
             .section = "exports",
             .key = "atlas_files",
             .slicer = "atlasFormats",
             .group = kExportGroup,
             .label = "Atlas files",
             .help = "Atlas files to write, comma-separated: ply (MeshLab, CloudCompare), vtp "
                     "(ParaView, Slicer), vtk (legacy ASCII, the same programs; not by default)"},
            OptionKind::Text,
            [](const ExportOptions& o) -> OptionValue { return to_string(o.atlas_files); },
            [](ExportOptions& o, const std::string& v) {
                o.atlas_files = parse_atlas_files(v, "--atlas-formats");
            }),
        F::integer(
            {.name = "mosaic_tile",
             .section = "exports",
             .key = "mosaic_tile",
             .slicer = "mosaicTile",
             .group = kExportGroup,
             .unit = "px",
             .min = 16,
             .max = 1024,
             .label = "Mosaic tile",
             .help = "Size of the views the mosaic draws whole (the regions' best views)"},
            [](auto& o) -> auto& { return o.mosaic_tile; }),
        F::text(
            {.name = "up",
             .section = "exports",
             .key = "up",
             .slicer = "up",
             .group = kExportGroup,
             .label = "Up in pictures",
             .help = "Which axis the pictures draw up: +x, -x, +y, -y, +z, -z (default: superior "
                     "when the reference is in a patient space, else +z)",
             .choices = up_choices()},
            OptionKind::Choice, [](const ExportOptions& o) { return F::text_or_unset(o.up); },
            [](ExportOptions& o, const std::string& v) { o.up = v; },
            [](ExportOptions& o) { o.up.clear(); }),
    };
    return table;
}

}  // namespace glint
