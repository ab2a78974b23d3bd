// Reading meshes from files.
//
// Formats: PLY (ASCII, binary little/big endian), STL (ASCII, binary), OBJ, OFF, glTF/GLB
// through assimp; VTK legacy POLYDATA (ASCII and binary big-endian, FIELD blocks,
// POINT_DATA scalars) with a reader of our own. Binary PLY and binary STL take a fast
// path of our own (a test proves it returns the same mesh as assimp).
#pragma once

#include "mesh/mesh.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

/// Which reader produced a mesh.
enum class MeshReader { FastPly, FastStl, Vtk, Assimp };

/// What loading did to the file's content on the way in: every repair is counted.
struct LoadReport {
    std::filesystem::path path;
    std::string format;  ///< "ply-binary-le", "stl-ascii", "vtk-binary", "obj", …
    MeshReader reader = MeshReader::Assimp;
    std::size_t file_vertices = 0;    ///< vertices as stored (STL: 3 per facet)
    std::size_t file_triangles = 0;   ///< triangles as stored (after fan-splitting polygons)
    std::size_t welded_vertices = 0;  ///< file vertices merged into another (identical position)
    /// OBJ through assimp: the importer's vertex count, one per face corner (file_vertices is
    /// the file's "v" lines); welding merged them back, which welded_vertices does not count.
    std::size_t importer_corner_vertices = 0;
    std::size_t degenerate_triangles = 0;  ///< dropped: repeated vertex or zero area
    std::size_t duplicate_triangles = 0;   ///< dropped: same three vertices as an earlier one
    std::size_t unused_vertices = 0;       ///< dropped: referenced by no triangle
    std::size_t split_polygons = 0;        ///< polygons with > 3 corners fan-split
    std::vector<std::string> warnings;     ///< anything else the reader noticed
    /// SHA-256 of the bytes parsed (lowercase hex): report.json's checksum of the input is of
    /// what was analysed, with no second read of the file (a 2 M-triangle pair is 100 MB).
    std::string sha256;
};

/// The triangle budget a LoadOptions starts with: 50 million triangles (about 2.4 GB once
/// loaded with normals and welding tables), unless changed by set_default_max_triangles()
/// (the CLI's --max-triangles).
inline constexpr std::uint64_t kDefaultMaxTriangles = 50'000'000;
[[nodiscard]] std::uint64_t default_max_triangles() noexcept;
/// Sets the budget later LoadOptions start with (process-wide; the CLI sets it once).
void set_default_max_triangles(std::uint64_t max_triangles) noexcept;

struct LoadOptions {
    bool weld = true;                ///< merge vertices with identical positions
    bool drop_degenerate = true;     ///< drop triangles with a repeated vertex / zero area
    bool drop_unused = true;         ///< drop vertices no triangle uses (keeps point clouds
                                     ///< when there are no triangles at all)
    bool compute_normals = true;     ///< angle-weighted vertex normals
    bool allow_fast_path = true;     ///< our own binary PLY / STL readers
    bool allow_points_only = false;  ///< accept a file without triangles (point cloud)
    /// Refuse a file with more triangles than this (as stored, after fan-splitting polygons
    /// and expanding scene instances), before reading its bulk where the format states counts.
    std::uint64_t max_triangles = default_max_triangles();
};

struct LoadedMesh {
    Mesh mesh;
    LoadReport report;
};

/// Loads a mesh file, detecting the format from content and extension.
/// The unit, when the file states one (mesh/units.h), is in mesh.unit.
/// \throw InputError missing file or a folder (bad input, like malformed content)
/// \throw IoError unreadable file
/// \throw InputError malformed or inconsistent content (message names file and line/element),
///        non-finite coordinates, index out of range, no triangles (unless allow_points_only),
///        a count the file's size cannot hold, more than options.max_triangles triangles, a
///        glTF node graph nested deeper than 64 or expanding to too many instances
/// \throw Cancelled SIGINT / SIGTERM arrived while reading (mesh/cancel.h)
[[nodiscard]] LoadedMesh load_mesh(const std::filesystem::path& path,
                                   const LoadOptions& options = {});

/// Loads with assimp only (no fast path); used to cross-check the fast readers.
[[nodiscard]] LoadedMesh load_mesh_assimp(const std::filesystem::path& path,
                                          const LoadOptions& options = {});

}  // namespace glint
