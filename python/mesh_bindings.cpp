// glint.Mesh and glint.load(): meshes as numpy views.
#include "python/bindings.h"

#include "mesh/error.h"
#include "mesh/output_guard.h"
#include "mesh/units.h"
#include "mesh/write.h"
#include "python/convert.h"
#include "python/interrupt.h"
#include "python/keywords.h"
#include "volume/load.h"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

namespace py = pybind11;

namespace glint::python {

namespace {

py::dict report_dict(const LoadReport& r) {
    py::dict d;
    d["path"] = r.path.string();
    d["format"] = r.format;
    d["file_vertices"] = r.file_vertices;
    d["file_triangles"] = r.file_triangles;
    d["welded_vertices"] = r.welded_vertices;
    d["importer_corner_vertices"] = r.importer_corner_vertices;
    d["degenerate_triangles"] = r.degenerate_triangles;
    d["duplicate_triangles"] = r.duplicate_triangles;
    d["unused_vertices"] = r.unused_vertices;
    d["split_polygons"] = r.split_polygons;
    d["warnings"] = r.warnings;
    return d;
}

py::dict surface_dict(const SurfaceReport& r) {
    py::dict d;
    d["voxels"] = r.voxels;
    d["cropped"] = r.cropped;
    d["spacing"] = std::array<double, 3>{r.spacing.x(), r.spacing.y(), r.spacing.z()};
    d["iso"] = r.iso;
    d["range"] = r.range;
    d["components_found"] = r.components_found;
    d["components_kept"] = r.components_kept;
    d["contour_triangles"] = r.contour_triangles;
    d["triangles"] = r.triangles;
    d["vertices"] = r.vertices;
    d["decimation_error_mm"] = r.decimation_error_mm;
    d["seconds"] = r.seconds;
    d["notes"] = r.notes;
    return d;
}

std::shared_ptr<MeshHandle> load(const std::filesystem::path& path, const SurfaceOptions& surface) {
    return run_interruptible_value([&] {
        LoadedSurface loaded = load_surface(path, surface);
        auto handle = std::make_shared<MeshHandle>();
        handle->mesh = std::move(loaded.mesh);
        handle->source = path.string();
        handle->report = std::move(loaded.report);
        handle->surface = std::move(loaded.surface);
        return handle;
    });
}

// glint.Mesh(positions, triangles, unit="mm"): copies of the arrays, checked as a loaded
// mesh is, with vertex normals. The unit defaults to millimetres (kArrayUnit, python/convert.h).
std::shared_ptr<MeshHandle> from_arrays(const py::object& positions, const py::object& triangles,
                                        const std::optional<std::string>& unit) {
    auto handle = std::make_shared<MeshHandle>();
    handle->mesh = mesh_from_arrays(
        positions, triangles, {"glint.Mesh", "glint.Mesh: positions", "glint.Mesh: triangles"});
    // Issue 23 item 15: unit='parsec' was kept; a unit is one glint can convert, or none.
    if (unit && canonical_unit(*unit).empty())
        throw InputError("glint.Mesh: unit '" + *unit +
                         "' is no length unit glint knows, expected "
                         "one of " +
                         known_units() + " (or None)");
    handle->mesh.unit = unit ? canonical_unit(*unit) : "";
    handle->source = "arrays";
    return handle;
}

py::object optional_string(const std::string& s) {
    return s.empty() ? py::object(py::none()) : py::object(py::str(s));
}

using MeshClass = py::class_<MeshHandle, std::shared_ptr<MeshHandle>>;

// The per-vertex arrays: read-only numpy views that keep the mesh alive.
void bind_mesh_arrays(MeshClass& mesh) {
    mesh.def_property_readonly(
            "positions",
            [](py::object self) {
                const Mesh& x = self.cast<MeshHandle&>().mesh;
                return readonly_view(x.positions.empty() ? nullptr : x.positions.front().data(),
                                     x.positions.size(), 3, self);
            },
            "N×3 float32 vertex positions (mesh units)")
        .def_property_readonly(
            "triangles",
            [](py::object self) {
                const Mesh& x = self.cast<MeshHandle&>().mesh;
                return readonly_view(x.triangles.empty() ? nullptr : x.triangles.front().data(),
                                     x.triangles.size(), 3, self);
            },
            "M×3 uint32 vertex ids, counter-clockwise seen from outside")
        .def_property_readonly(
            "normals",
            [](py::object self) {
                const Mesh& x = self.cast<MeshHandle&>().mesh;
                return readonly_view(x.normals.empty() ? nullptr : x.normals.front().data(),
                                     x.normals.size(), 3, self);
            },
            "N×3 float32 unit vertex normals (angle-weighted)")
        .def_property_readonly(
            "colors",
            [](py::object self) -> py::object {
                const Mesh& x = self.cast<MeshHandle&>().mesh;
                if (x.colors.empty()) return py::none();
                return readonly_view(x.colors.front().data(), x.colors.size(), 3, self);
            },
            "N×3 uint8 sRGB vertex colours, or None")
        .def_property_readonly(
            "labels",
            [](py::object self) -> py::object {
                const Mesh& x = self.cast<MeshHandle&>().mesh;
                if (x.labels.empty()) return py::none();
                return readonly_view(x.labels.data(), x.labels.size(), 1, self);
            },
            "per-vertex int32 labels (0 = none), or None")
        .def_property_readonly(
            "scalars",
            [](py::object self) {
                py::dict d;
                for (const ScalarField& f : self.cast<MeshHandle&>().mesh.scalars)
                    d[py::str(f.name)] = readonly_view(f.values.data(), f.values.size(), 1, self);
                return d;
            },
            "named per-vertex float32 fields (a dict of numpy views)");
}

// Copies, moves, pickling and the other libraries' meshes (python/convert.h).
void bind_mesh_conversions(MeshClass& mesh) {
    mesh.def_static("from_numpy", &from_arrays, py::arg("positions"), py::arg("triangles"),
                    py::arg("unit") = kArrayUnit,
                    "The same as glint.Mesh(positions, triangles, unit).")
        .def("to_numpy", &to_numpy,
             "(positions, triangles) as new writable arrays: N×3 float64 and M×3 int64 (numpy's "
             "defaults; float32 positions convert exactly). glint.Mesh(*mesh.to_numpy()) is the "
             "same mesh.")
        .def("to_open3d", &to_open3d,
             "An open3d.geometry.TriangleMesh with vertex normals (and colours). ImportError "
             "when open3d is missing (Debian: python3-open3d).")
        .def("to_pyvista", &to_pyvista,
             "A pyvista.PolyData with point data Normals, colors, label and every scalar. "
             "ImportError when pyvista is missing.")
        .def("to_trimesh", &to_trimesh,
             "A trimesh.Trimesh (process=False: vertices and faces as they are) with vertex "
             "normals, colours and units. ImportError when trimesh is missing.")
        .def(
            "copy", [](const MeshHandle& h) { return std::make_shared<MeshHandle>(h); },
            "A new mesh with copies of every array.")
        .def("__copy__", [](const MeshHandle& h) { return std::make_shared<MeshHandle>(h); })
        .def(
            "__deepcopy__",
            [](const MeshHandle& h, const py::dict&) { return std::make_shared<MeshHandle>(h); },
            py::arg("memo"))
        .def("transform", &transformed, py::arg("transform"),
             R"(A new mesh moved by `transform`: a 4×4 affine matrix (last row 0 0 0 1) or a
pair (R, t) of a 3×3 matrix and a translation, applied as R·p + t (Fit.matrix moves an examined
mesh into the reference's frame). This mesh is left as it is: its arrays are read-only views
that others may hold, so glint returns a new mesh where Open3D moves in place. Normals are
recomputed; a mirror (negative determinant) reverses the triangles so they stay
counter-clockwise seen from outside. A singular matrix is refused. The new mesh has no load
report and its source says it was transformed (report.json must not name the file as the input).)")
        .def(py::pickle([](const py::object& self) { return mesh_state(self); },
                        [](const py::tuple& state) { return mesh_from_state(state); }));
}

}  // namespace

namespace {

std::string type_name(const py::handle& value) {
    return py::cast<std::string>(py::str(value.get_type().attr("__name__")));
}

}  // namespace

std::optional<std::filesystem::path> path_argument(const py::object& value, const char* function,
                                                   const char* keyword) {
    if (value.is_none()) return std::nullopt;
    if (!py::isinstance<py::str>(value) && !py::hasattr(value, "__fspath__"))
        throw py::type_error(std::string(function) + "(): " + keyword +
                             " must be a str, os.PathLike or None, not " + type_name(value));
    return py::cast<std::filesystem::path>(value);
}

bool bool_argument(const py::object& value, const char* function, const char* keyword) {
    if (!py::isinstance<py::bool_>(value))
        throw py::type_error(std::string(function) + "(): " + keyword +
                             " must be True or False, not " + type_name(value));
    return py::cast<bool>(value);
}

std::shared_ptr<MeshHandle> mesh_argument(const MeshLike& argument, const SurfaceOptions& surface,
                                          const char* role) {
    const py::handle value = argument.value;
    if (py::isinstance<MeshHandle>(value)) return py::cast<std::shared_ptr<MeshHandle>>(value);
    if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__")) {
        auto loaded = load(py::cast<std::filesystem::path>(value), surface);
        if (loaded->report) warn(loaded->report->warnings);
        return loaded;
    }
    if (auto converted = converted_mesh(value, role)) return *converted;
    throw py::type_error(std::string(role) +
                         " must be a glint.Mesh, a path, a (vertices, triangles) pair of arrays "
                         "or a mesh with vertices and triangles (Open3D, trimesh, PyVista), "
                         "not " +
                         type_name(value));
}

namespace {

// glint.as_mesh() and glint.load().
void bind_mesh_functions(py::module_& m) {
    m.def(
        "as_mesh",
        [](const MeshLike& value, const py::kwargs& kwargs) {
            Keywords k;
            apply_keywords(k, kwargs, kSurfaceKeywords, "as_mesh");
            return mesh_argument(value, k.surface, "mesh");
        },
        py::arg("mesh"),
        "The glint.Mesh that glint.analyse and glint.register make of their arguments: a "
        "glint.Mesh as it is, a path loaded (keywords as glint.load's), a (vertices, "
        "triangles) pair of arrays, or an Open3D (legacy or tensor), trimesh or PyVista mesh "
        "converted (copied and checked). Convert once to reuse a mesh in many calls.");
    m.def(
        "load",
        [](const py::object& path, py::kwargs kwargs) {
            // note: a py::object rather than a path parameter: pybind11's own refusal of a
            // wrong type is a message of several lines listing the signatures.
            if (!py::isinstance<py::str>(path) && !py::hasattr(path, "__fspath__"))
                throw py::type_error("load(): path must be a str or os.PathLike, not " +
                                     type_name(path));
            Keywords k;
            apply_keywords(k, kwargs, kSurfaceKeywords, "load");
            auto loaded = load(py::cast<std::filesystem::path>(path), k.surface);
            if (loaded->report) warn(loaded->report->warnings);
            return loaded;
        },
        py::arg("path"),
        ("Loads a mesh file (PLY, STL, OBJ, OFF, glTF, VTK) or extracts the iso-surface of a volume (MetaImage, "
         "NIfTI, NRRD, DICOM folder; iso= required). Keywords: " +
         keyword_names(kSurfaceKeywords) +
         " (as glint surface's flags). Raises glint.InputError, glint.IoError.")
            .c_str());
}

}  // namespace

void bind_mesh(py::module_& m) {
    MeshClass mesh(m, "Mesh", R"(A triangle mesh.

Arrays are read-only numpy views into the mesh (no copy); they keep the mesh alive. Copy
them (numpy.array(mesh.positions), mesh.to_numpy()) to change them; copy() and transform()
give new meshes. Meshes pickle (without their load report). Every glint function that takes a
mesh also takes a path, a (vertices, triangles) pair of arrays or a mesh of Open3D, trimesh or
PyVista.)");
    mesh.def(
        py::init(&from_arrays), py::arg("positions"), py::arg("triangles"),
        py::arg("unit") = kArrayUnit,
        "A mesh from an N×3 array of positions and an M×3 array of vertex ids (counter-clockwise seen from "
        "outside); copied, checked as a loaded mesh is, vertex normals computed. unit: the "
        "coordinates' length unit, \"mm\" unless given (CT-derived surfaces are in millimetres), "
        "so that the atlas fields keep their names (shape_change_mm); None for a mesh whose unit "
        "is unknown (the fields then end in _units).");
    bind_mesh_arrays(mesh);
    mesh.def_property_readonly(
            "unit", [](const MeshHandle& h) { return optional_string(h.mesh.unit); },
            "length unit the file states (\"mm\", …), or None")
        .def_property_readonly(
            "source", [](const MeshHandle& h) { return h.source; },
            "the file, or what made the mesh")
        .def_property_readonly(
            "report",
            [](const MeshHandle& h) -> py::object {
                if (!h.report) return py::none();
                py::dict d = report_dict(*h.report);
                d["surface"] =
                    h.surface ? py::object(surface_dict(*h.surface)) : py::object(py::none());
                return d;
            },
            "what loading repaired (welded, dropped, split) and, for a volume, the surface extraction; None for arrays")
        .def_property_readonly("vertex_count",
                               [](const MeshHandle& h) { return h.mesh.vertex_count(); })
        .def_property_readonly("triangle_count",
                               [](const MeshHandle& h) { return h.mesh.triangle_count(); })
        .def(
            "save",
            [](const MeshHandle& h, const std::filesystem::path& path) {
                // As the command line's -o: never over an input, complete or absent.
                refuse_output_over_inputs(path);
                run_interruptible([&] { write_mesh(h.mesh, path); });
            },
            py::arg("path"),
            ("Writes the mesh by extension: " + std::string(kWritableMeshExtensions) +
             ". PLY, VTK and VTP keep colours, labels and scalars; STL, OBJ and OFF hold the "
             "geometry (and the unit in a comment). Written to a temporary name and renamed, "
             "never over a file this process read.")
                .c_str());
    bind_mesh_conversions(mesh);
    mesh.def("__repr__", [](const MeshHandle& h) {
        return "<glint.Mesh " + std::to_string(h.mesh.vertex_count()) + " vertices, " +
               std::to_string(h.mesh.triangle_count()) + " triangles from " + h.source + ">";
    });

    bind_mesh_functions(m);
}

}  // namespace glint::python
