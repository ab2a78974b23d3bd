// Meshes in and out of glint from the Python ecosystem: numpy (V, F) arrays, Open3D (legacy
// and tensor), trimesh and PyVista objects. Inputs are read by duck typing (no import of the
// other library is needed to accept its mesh); outputs import the library and say how to
// install it when it is missing.
#include "python/convert.h"

#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/units.h"
#include "mesh/validate.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

namespace py = pybind11;

namespace glint::python {

namespace {

std::string text_of(py::handle value) { return py::cast<std::string>(py::str(value)); }

std::string shape_of(const py::array& a) { return text_of(py::repr(a.attr("shape"))); }

// "open3d.cpu.pybind.geometry.TriangleMesh": what report.json records for a converted input.
std::string type_name(py::handle value) {
    const py::handle type = value.get_type();
    return text_of(type.attr("__module__")) + "." + text_of(type.attr("__qualname__"));
}

// N×3 positions: numbers (no bool, string or object arrays), every one finite.
std::vector<Vec3f> positions_from(py::handle value, const std::string& label) {
    const py::array any = py::module_::import("numpy").attr("asarray")(value);
    const char kind = any.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw InputError(label + " must be an N×3 array of numbers, found dtype " +
                         text_of(any.dtype()));
    if (any.ndim() != 2 || any.shape(1) != 3)
        throw InputError(label + " must be an N×3 array, found shape " + shape_of(any));
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(any);
    const auto p = a.unchecked<2>();
    std::vector<Vec3f> out(static_cast<std::size_t>(p.shape(0)));
    for (py::ssize_t i = 0; i < p.shape(0); ++i) {
        for (py::ssize_t c = 0; c < 3; ++c)
            if (!std::isfinite(p(i, c)))
                throw InputError(label + " must be finite, found " +
                                 text_of(py::repr(py::float_(p(i, c)))) + " in row " +
                                 std::to_string(i));
        out[static_cast<std::size_t>(i)] = Vec3d(p(i, 0), p(i, 1), p(i, 2)).cast<float>();
    }
    return out;
}

// M×3 vertex ids: integers (a float index was truncated once: issue 23 item 15) in range.
std::vector<Triangle> triangles_from(py::handle value, std::size_t vertices,
                                     const std::string& label, const std::string& owner) {
    const py::array any = py::module_::import("numpy").attr("asarray")(value);
    const char kind = any.dtype().kind();
    if (kind != 'i' && kind != 'u')
        throw InputError(label + " must be an array of integers (vertex indices), found dtype " +
                         text_of(any.dtype()));
    if (any.ndim() != 2 || any.shape(1) != 3)
        throw InputError(label + " must be an M×3 array, found shape " + shape_of(any));
    // note: unsigned arrays are read as unsigned: uint64 2^63+1 cast to int64 was printed as
    // a negative vertex (issue 52).
    std::vector<Triangle> out;
    const auto fill = [&](auto ids) {
        // note: the converted array must outlive the view (unchecked() does not hold it).
        const auto t = ids.template unchecked<2>();
        out.resize(static_cast<std::size_t>(t.shape(0)));
        for (py::ssize_t i = 0; i < t.shape(0); ++i)
            for (py::ssize_t c = 0; c < 3; ++c) {
                const auto v = t(i, c);
                bool negative = false;
                if constexpr (std::is_signed_v<std::remove_cv_t<decltype(v)>>) negative = v < 0;
                if (negative || static_cast<std::uint64_t>(v) >= vertices)
                    throw InputError(owner + ": triangle " + std::to_string(i) + " uses vertex " +
                                     std::to_string(v) + ", mesh has " + std::to_string(vertices) +
                                     " vertices");
                out[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)] =
                    static_cast<std::uint32_t>(v);
            }
    };
    if (kind == 'u')
        fill(py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(any));
    else fill(py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(any));
    return out;
}

// A tensor (Open3D's, torch's) or array as a numpy array on the host.
py::object host_array(py::object value) {
    if (py::hasattr(value, "cpu")) value = value.attr("cpu")();
    if (py::hasattr(value, "numpy")) value = value.attr("numpy")();
    return value;
}

// PyVista's flat face list [3, a, b, c, 3, …] as M×3; any other polygon is refused.
py::object pyvista_triangles(py::handle faces, const std::string& label) {
    const py::array any = py::module_::import("numpy").attr("asarray")(faces);
    const auto flat =
        py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(any);
    const auto n = static_cast<std::size_t>(flat ? flat.size() : 0);
    const std::int64_t* ids = flat ? flat.data() : nullptr;
    bool triangles = flat && n % 4 == 0;
    for (std::size_t i = 0; triangles && i < n; i += 4) triangles = ids[i] == 3;
    if (!triangles)
        throw InputError(label +
                         " holds faces that are not triangles; glint takes triangle meshes "
                         "(PyVista: mesh.triangulate())");
    py::array_t<std::int64_t> out({static_cast<py::ssize_t>(n / 4), py::ssize_t{3}});
    std::int64_t* row = out.mutable_data();
    for (std::size_t i = 0; i < n; i += 4, row += 3) std::copy(ids + i + 1, ids + i + 4, row);
    return out;
}

// The (positions, triangles) of a mesh object of another library, by the attributes it has;
// nullopt when it has none of them.
std::optional<std::pair<py::object, py::object>> duck_arrays(py::handle value,
                                                             const std::string& role,
                                                             std::string& labels) {
    auto attr = [&](const char* name) { return py::getattr(value, name); };
    if (py::hasattr(value, "vertex") && py::hasattr(value, "triangle")) {  // Open3D tensor
        labels = ".vertex.positions|.triangle.indices";
        const py::object v = attr("vertex"), t = attr("triangle");
        return std::pair{host_array(v.attr("__getitem__")("positions")),
                         host_array(t.attr("__getitem__")("indices"))};
    }
    if (py::hasattr(value, "vertices") && py::hasattr(value, "triangles")) {  // Open3D legacy
        labels = ".vertices|.triangles";
        return std::pair{attr("vertices"), attr("triangles")};
    }
    if (py::hasattr(value, "vertices") && py::hasattr(value, "faces")) {  // trimesh
        labels = ".vertices|.faces";
        return std::pair{attr("vertices"), attr("faces")};
    }
    if (py::hasattr(value, "points") && py::hasattr(value, "faces")) {  // PyVista PolyData
        labels = ".points|.faces";
        return std::pair{attr("points"), pyvista_triangles(attr("faces"), role + ".faces")};
    }
    return std::nullopt;
}

}  // namespace

Mesh mesh_from_arrays(py::handle positions, py::handle triangles, const ArrayLabels& labels) {
    Mesh mesh;
    mesh.positions = positions_from(positions, labels.positions);
    mesh.triangles =
        triangles_from(triangles, mesh.positions.size(), labels.triangles, labels.owner);
    check_mesh(mesh, labels.owner);
    compute_vertex_normals(mesh);
    return mesh;
}

std::optional<std::shared_ptr<MeshHandle>> converted_mesh(py::handle value,
                                                          const std::string& role) {
    auto handle = std::make_shared<MeshHandle>();
    if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
        const auto items = py::reinterpret_borrow<py::sequence>(value);
        if (items.size() != 2)
            throw InputError(role + ": a sequence must be (vertices, triangles), found " +
                             std::to_string(items.size()) + " items");
        handle->mesh = mesh_from_arrays(items[0], items[1],
                                        {role, role + "[0] (vertices)", role + "[1] (triangles)"});
        handle->mesh.unit = kArrayUnit;
        handle->source = "arrays";
        return handle;
    }
    std::string names;
    const auto arrays = duck_arrays(value, role, names);
    if (!arrays) return std::nullopt;
    const std::size_t bar = names.find('|');
    handle->mesh =
        mesh_from_arrays(arrays->first, arrays->second,
                         {role, role + names.substr(0, bar), role + names.substr(bar + 1)});
    // trimesh states its unit ("millimeters"); glint keeps it when it knows the word. Open3D
    // and PyVista state none: millimetres, as glint.Mesh takes arrays (kArrayUnit), so that an
    // analysis of their meshes writes the same field names (issue 51: shape_change_units).
    handle->mesh.unit = kArrayUnit;
    if (py::hasattr(value, "units") && py::isinstance<py::str>(py::getattr(value, "units")))
        handle->mesh.unit = canonical_unit(text_of(py::getattr(value, "units")));
    handle->source = type_name(value);
    return handle;
}

}  // namespace glint::python

namespace glint::python {

namespace {

// The module of another library, or ImportError saying how to install it.
py::module_ import_or_explain(const char* module, const char* method, const char* install) {
    try {
        return py::module_::import(module);
    } catch (const py::error_already_set& e) {
        if (!e.matches(PyExc_ImportError)) throw;
        throw py::import_error(std::string("glint.Mesh.") + method + "() needs the " + module +
                               " module, which is not importable here: " + install);
    }
}

py::array copy_of(const py::array& view, const char* dtype) {
    return py::module_::import("numpy").attr("array")(view, py::arg("dtype") = dtype);
}

}  // namespace

py::tuple to_numpy(const py::object& self) {
    return py::make_tuple(copy_of(self.attr("positions"), "float64"),
                          copy_of(self.attr("triangles"), "int64"));
}

py::object to_open3d(const py::object& self) {
    const py::module_ o3d = import_or_explain("open3d", "to_open3d",
                                              "apt install python3-open3d (Debian) or pip "
                                              "install open3d");
    const py::object utility = o3d.attr("utility");
    const py::object out =
        o3d.attr("geometry")
            .attr("TriangleMesh")(
                utility.attr("Vector3dVector")(copy_of(self.attr("positions"), "float64")),
                utility.attr("Vector3iVector")(copy_of(self.attr("triangles"), "int32")));
    out.attr("vertex_normals") =
        utility.attr("Vector3dVector")(copy_of(self.attr("normals"), "float64"));
    if (const py::object colors = self.attr("colors"); !colors.is_none())
        out.attr("vertex_colors") =
            utility.attr("Vector3dVector")(copy_of(colors, "float64").attr("__truediv__")(255.0));
    return out;
}

py::object to_pyvista(const py::object& self) {
    const py::module_ pv = import_or_explain("pyvista", "to_pyvista",
                                             "pip install pyvista (Debian 12 does not package it)");
    const py::module_ np = py::module_::import("numpy");
    const py::array triangles = copy_of(self.attr("triangles"), "int64");
    // PyVista's flat face list: each face as its vertex count (3) and its vertex ids.
    const py::object counts =
        np.attr("full")(py::make_tuple(triangles.shape(0), 1), 3, py::arg("dtype") = "int64");
    const py::object faces = np.attr("hstack")(py::make_tuple(counts, triangles)).attr("ravel")();
    const py::object out = pv.attr("PolyData")(copy_of(self.attr("positions"), "float64"), faces);
    const py::object data = out.attr("point_data");
    data["Normals"] = copy_of(self.attr("normals"), "float32");
    if (const py::object colors = self.attr("colors"); !colors.is_none())
        data["colors"] = copy_of(colors, "uint8");
    if (const py::object labels = self.attr("labels"); !labels.is_none())
        data["label"] = copy_of(labels, "int32");
    for (const auto& [name, values] : py::cast<py::dict>(self.attr("scalars")))
        data[name] = copy_of(py::reinterpret_borrow<py::array>(values), "float32");
    return out;
}

py::object to_trimesh(const py::object& self) {
    const py::module_ trimesh = import_or_explain(
        "trimesh", "to_trimesh", "pip install trimesh (Debian 12 does not package it)");
    py::dict args;
    args["vertices"] = copy_of(self.attr("positions"), "float64");
    args["faces"] = copy_of(self.attr("triangles"), "int64");
    args["vertex_normals"] = copy_of(self.attr("normals"), "float64");
    if (const py::object colors = self.attr("colors"); !colors.is_none())
        args["vertex_colors"] = copy_of(colors, "uint8");
    args["process"] = false;  // glint's vertices and triangles as they are, in their order
    const py::object out = trimesh.attr("Trimesh")(**args);
    if (const py::object unit = self.attr("unit"); !unit.is_none()) out.attr("units") = unit;
    return out;
}

}  // namespace glint::python
