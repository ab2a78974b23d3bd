// glint.Mesh and glint.load(): meshes as numpy views.
#include "python/bindings.h"

#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/units.h"
#include "mesh/validate.h"
#include "mesh/write.h"
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

// glint.Mesh(positions, triangles, unit=None): copies of the arrays, checked as a loaded
// mesh is, with vertex normals.
std::shared_ptr<MeshHandle> from_arrays(
    const py::array_t<float, py::array::c_style | py::array::forcecast>& positions,
    const py::object& triangle_object, const std::optional<std::string>& unit) {
    // Issue 23 item 15: float indices were truncated (1.7 became vertex 1) by a forced cast.
    const py::array triangle_array = py::array::ensure(triangle_object);
    if (!triangle_array)
        throw InputError("glint.Mesh: triangles must be an M×3 array of vertex indices");
    const char kind = triangle_array.dtype().kind();
    if (kind != 'i' && kind != 'u')
        throw InputError(
            "glint.Mesh: triangles must be an array of integers (vertex indices), "
            "found dtype " +
            py::cast<std::string>(py::str(triangle_array.dtype())));
    const auto triangles =
        py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(
            triangle_array);
    if (!triangles)
        throw InputError("glint.Mesh: triangles do not fit 64-bit integers, found dtype " +
                         py::cast<std::string>(py::str(triangle_array.dtype())));
    if (positions.ndim() != 2 || positions.shape(1) != 3)
        throw InputError("glint.Mesh: positions must be an N×3 array, found shape " +
                         py::cast<std::string>(py::repr(positions.attr("shape"))));
    if (triangles.ndim() != 2 || triangles.shape(1) != 3)
        throw InputError("glint.Mesh: triangles must be an M×3 array, found shape " +
                         py::cast<std::string>(py::repr(triangles.attr("shape"))));
    auto handle = std::make_shared<MeshHandle>();
    Mesh& mesh = handle->mesh;
    const auto p = positions.unchecked<2>();
    mesh.positions.resize(static_cast<std::size_t>(p.shape(0)));
    for (py::ssize_t i = 0; i < p.shape(0); ++i)
        mesh.positions[static_cast<std::size_t>(i)] = Vec3f(p(i, 0), p(i, 1), p(i, 2));
    const auto t = triangles.unchecked<2>();
    mesh.triangles.resize(static_cast<std::size_t>(t.shape(0)));
    for (py::ssize_t i = 0; i < t.shape(0); ++i)
        for (py::ssize_t c = 0; c < 3; ++c) {
            const std::int64_t v = t(i, c);
            if (v < 0 || v >= p.shape(0))
                throw InputError("glint.Mesh: triangle " + std::to_string(i) + " uses vertex " +
                                 std::to_string(v) + ", mesh has " + std::to_string(p.shape(0)) +
                                 " vertices");
            mesh.triangles[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)] =
                static_cast<std::uint32_t>(v);
        }
    // Issue 23 item 15: unit='parsec' was kept; a unit is one glint can convert, or none.
    if (unit && canonical_unit(*unit).empty())
        throw InputError("glint.Mesh: unit '" + *unit +
                         "' is no length unit glint knows, expected "
                         "one of " +
                         known_units() + " (or None)");
    mesh.unit = unit ? canonical_unit(*unit) : "";
    check_mesh(mesh, "glint.Mesh");
    compute_vertex_normals(mesh);
    handle->source = "arrays";
    return handle;
}

py::object optional_string(const std::string& s) {
    return s.empty() ? py::object(py::none()) : py::object(py::str(s));
}

}  // namespace

std::shared_ptr<MeshHandle> mesh_argument(py::handle value, const SurfaceOptions& surface,
                                          const char* role) {
    if (py::isinstance<MeshHandle>(value)) return py::cast<std::shared_ptr<MeshHandle>>(value);
    std::filesystem::path path;
    try {
        path = py::cast<std::filesystem::path>(value);
    } catch (const py::cast_error&) {
        throw py::type_error(std::string(role) + " must be a glint.Mesh or a path, not " +
                             py::cast<std::string>(py::str(value.get_type().attr("__name__"))));
    }
    return load(path, surface);
}

void bind_mesh(py::module_& m) {
    py::class_<MeshHandle, std::shared_ptr<MeshHandle>> mesh(m, "Mesh", R"(A triangle mesh.

Arrays are read-only numpy views into the mesh (no copy); they keep the mesh alive. Copy
them (numpy.array(mesh.positions)) to change them.)");
    mesh.def(
            py::init(&from_arrays), py::arg("positions"), py::arg("triangles"),
            py::arg("unit") = py::none(),
            "A mesh from an N×3 array of positions and an M×3 array of vertex ids (counter-clockwise seen from "
            "outside); copied, checked as a loaded mesh is, vertex normals computed.")
        .def_property_readonly(
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
            "named per-vertex float32 fields (a dict of numpy views)")
        .def_property_readonly(
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
                run_interruptible([&] { write_mesh(h.mesh, path); });
            },
            py::arg("path"),
            "Writes the mesh (.ply, .vtk or .vtp by extension) with its colours and scalars.")
        .def("__repr__", [](const MeshHandle& h) {
            return "<glint.Mesh " + std::to_string(h.mesh.vertex_count()) + " vertices, " +
                   std::to_string(h.mesh.triangle_count()) + " triangles from " + h.source + ">";
        });

    m.def(
        "load",
        [](const std::filesystem::path& path, py::kwargs kwargs) {
            Keywords k;
            apply_keywords(k, kwargs, kSurfaceKeywords, "load");
            return load(path, k.surface);
        },
        py::arg("path"),
        ("Loads a mesh file (PLY, STL, OBJ, OFF, glTF, VTK) or extracts the iso-surface of a volume (MetaImage, "
         "NIfTI, NRRD, DICOM folder; iso= required). Keywords: " +
         keyword_names(kSurfaceKeywords) +
         " (as glint surface's flags). Raises glint.InputError, glint.IoError.")
            .c_str());
}

}  // namespace glint::python
