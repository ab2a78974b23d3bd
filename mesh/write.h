// Writing meshes, in the forms the viewers people use actually read (each proven by loading a
// written file with the real program: tests/tools/viewers_test.sh):
//   PLY  binary; MeshLab maps only a vertex property named `quality`; CloudCompare 2.11 (run
//        with -SILENT: tests/tools/viewers_test.sh) imports only properties named
//        `scalar_<name>` and shows them as <name>: WriteOptions names every scalar that way and adds the one `quality` copy.
//        glint's PLY reader reads `scalar_<name>` back as <name> (mesh/detail/ply_reader.cpp).
// The scalars come first in every format, so the first one is the active scalar a viewer
// opens on (VTK: the first SCALARS block, VTP: PointData's Scalars attribute).
//   VTK  legacy ASCII (CloudCompare 2.11 refuses binary legacy VTK; its reader also needs a
//        POINT_DATA line before every array, which VTK accepts after an empty CELL_DATA
//        section: mesh/write_vtk.cpp), for ParaView, 3D Slicer and CloudCompare. VTK's
//        legacy ASCII reader cannot parse NaN: NaN is written as WriteOptions::vtk_legacy_nan.
//   VTP  VTK XML PolyData, binary (base64) arrays: exact values, NaN kept (ParaView, Slicer).
//   STL (binary), OBJ, OFF: positions and triangles only, for tools that read nothing else
//        (slicers, printers, CAD); the unit in the comment glint's reader looks for.
// Files are written to a temporary name in the same folder and renamed into place.
#pragma once

#include "mesh/mesh.h"

#include <filesystem>

namespace glint {

/// The extensions write_mesh knows, for messages and front ends' help.
inline constexpr const char* kWritableMeshExtensions = ".ply, .vtk, .vtp, .stl, .obj or .off";

/// Whether write_mesh writes `path` (by its extension, any case).
[[nodiscard]] bool is_writable_mesh_path(const std::filesystem::path& path);

struct WriteOptions {
    bool write_normals = true;
    bool write_colors = true;   ///< when mesh.colors is set
    bool write_scalars = true;  ///< every ScalarField as a float property
    bool write_labels = true;   ///< labels as an int property "label"
    /// PLY: this scalar also as the property `quality` (MeshLab's only per-vertex scalar);
    /// empty: none. \throw InputError from the writers when the mesh has no such scalar.
    std::string quality_scalar;
    /// PLY: every scalar named `scalar_<name>` instead of `<name>` (the names CloudCompare
    /// imports; it shows them as <name>). Each scalar is still written once.
    bool cloudcompare_names = false;
    /// VTK legacy ASCII: the number written for NaN (VTK's ASCII reader fails on "nan").
    float vtk_legacy_nan = -9999.0f;
};

/// Binary little-endian PLY. \throw IoError on any write failure (nothing left behind).
void write_ply(const Mesh& mesh, const std::filesystem::path& path,
               const WriteOptions& options = {});

/// VTK legacy POLYDATA, ASCII: normals, colours (COLOR_SCALARS), scalars and labels as point
/// data, each array after its own POINT_DATA line (the later ones after "CELL_DATA 0"); NaN written as options.vtk_legacy_nan; the
/// unit, when known, in the title line ("glint mesh unit mm"). \throw IoError.
void write_vtk(const Mesh& mesh, const std::filesystem::path& path,
               const WriteOptions& options = {});

/// VTK XML PolyData (.vtp), arrays inline as base64 binary (little endian, UInt32 headers):
/// float positions, normals, scalars (NaN kept), Int32 labels, UInt8 colours.
/// \throw IoError on any write failure.
void write_vtp(const Mesh& mesh, const std::filesystem::path& path,
               const WriteOptions& options = {});

/// Binary STL: one facet per triangle with its face normal; the unit in the 80-byte header
/// ("glint binary STL, unit mm"). Per-vertex arrays are not written. \throw IoError.
void write_stl(const Mesh& mesh, const std::filesystem::path& path);

/// Wavefront OBJ, ASCII: `v` and `f` lines (positions exact: %.9g), "# unit mm" when known.
/// \throw IoError.
void write_obj(const Mesh& mesh, const std::filesystem::path& path);

/// OFF, ASCII: positions and triangles, "# unit mm" after the OFF line when known.
/// \throw IoError.
void write_off(const Mesh& mesh, const std::filesystem::path& path);

/// Writes by extension (.ply, .vtk, .vtp with every array; .stl, .obj, .off geometry only);
/// \throw InputError for another extension.
void write_mesh(const Mesh& mesh, const std::filesystem::path& path,
                const WriteOptions& options = {});

}  // namespace glint
