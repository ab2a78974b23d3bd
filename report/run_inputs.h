// Run set-up, once for every front end (command line, Slicer module, Python, scenarios): the
// surfaces of a run with how they were obtained, and the provenance report.json records
// (the command line, every input with its checksum, what loading repaired).
#pragma once

#include "mesh/mesh.h"
#include "volume/load.h"
#include "volume/surface.h"

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

/// One input of a run, for the report.
struct InputRecord {
    std::string role;            ///< "reference", "examined", "fit", "scenario", "calibration"
    std::filesystem::path path;  ///< empty for a generated mesh
    std::string description;     ///< e.g. "phantom condyle ico 5"
    std::size_t vertices = 0;
    std::size_t triangles = 0;
    /// The patient space its coordinates are in (report/orientation.h): "LPS" for a volume's
    /// surface, what a mesh file states (SPACE=), "" when unknown.
    std::string space;
    /// SHA-256 of the bytes read (mesh files); empty: report.json checksums the file itself.
    std::string sha256;
};

/// A surface of a run and how it was obtained.
struct RunInput {
    Mesh mesh;
    InputRecord record;
    std::vector<std::string> warnings;  ///< what loading repaired or noticed, each naming the file
};

/// A mesh file, or the surface of a volume (volume/load.h), as the input `role`.
/// \throw as load_surface.
[[nodiscard]] RunInput load_run_input(const std::string& role, const std::filesystem::path& path,
                                      const SurfaceOptions& surface);

/// The reference and examined inputs of a pair. Two mesh files are read at once, on two
/// threads; volumes one after the other (ITK's and VTK's readers are not known to be safe side
/// by side). The reference's error is thrown first, as when read in turn. `loaded` (when set)
/// is told each role once its input is read, on the calling thread: "reference", then
/// "examined" (progress).
[[nodiscard]] std::pair<RunInput, RunInput> load_run_pair(
    const std::filesystem::path& reference, const std::filesystem::path& examined,
    const SurfaceOptions& surface, const std::function<void(std::string_view role)>& loaded = {});

/// A mesh made or loaded elsewhere (a phantom, a Python array) as the input `role`; `path`
/// when it came from a file.
[[nodiscard]] RunInput mesh_run_input(const std::string& role, Mesh mesh, std::string description,
                                      std::filesystem::path path = {},
                                      std::vector<std::string> warnings = {});

/// What report.json records of where a run came from.
struct RunRecord {
    std::string command_line;           ///< argv joined, or the call that started the run
    std::vector<InputRecord> inputs;    ///< checksummed when written into report.json
    std::vector<std::string> warnings;  ///< set-up warnings (load repairs), before the analysis'
    /// Records an input and its warnings.
    void add(const RunInput& input);
    /// Records a file that is no surface (a fit, a calibration, a scenario).
    void add_file(const std::string& role, const std::filesystem::path& path,
                  std::string description = {});
};

}  // namespace glint
