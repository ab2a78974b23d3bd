// What the binding files share: the Python-side mesh object and the array views.
#pragma once

#include "mesh/io.h"
#include "mesh/mesh.h"
#include "volume/surface.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glint::python {

/// glint.Mesh: a mesh and where it came from. Python holds it through a shared_ptr; the
/// numpy arrays it hands out are views into `mesh` that keep this object alive.
struct MeshHandle {
    Mesh mesh;
    std::string source;                    ///< the file, or a description ("arrays", "atlas")
    std::optional<LoadReport> report;      ///< when loaded from a file
    std::optional<SurfaceReport> surface;  ///< when extracted from a volume
};

/// A read-only numpy view (rows × cols) of `rows` contiguous records of `cols` T each,
/// owned by `owner` (no copy). Empty data gives a (0, cols) array.
template <class T>
pybind11::array readonly_view(const T* data, std::size_t rows, std::size_t cols,
                              pybind11::handle owner) {
    std::vector<pybind11::ssize_t> shape{static_cast<pybind11::ssize_t>(rows)};
    std::vector<pybind11::ssize_t> strides{static_cast<pybind11::ssize_t>(cols * sizeof(T))};
    if (cols > 1) {
        shape.push_back(static_cast<pybind11::ssize_t>(cols));
        strides.push_back(sizeof(T));
    }
    pybind11::array_t<T> view(shape, strides, rows == 0 ? nullptr : data, owner);
    view.attr("setflags")(pybind11::arg("write") = false);
    return view;
}

/// A mesh argument as Python passes it; converted by mesh_argument (its type caster only
/// gives help() the types it takes).
struct MeshLike {
    pybind11::object value;
};

/// A mesh argument: a glint.Mesh as it is; a path (str, os.PathLike) loaded as glint.load
/// does (a volume with surface.iso; loads with the GIL released, issues its load warnings); a
/// (V, F) pair of arrays or a mesh of Open3D, trimesh or PyVista (python/convert.h).
/// \throw pybind11::type_error for anything else, InputError for arrays that are no mesh.
[[nodiscard]] std::shared_ptr<MeshHandle> mesh_argument(const MeshLike& value,
                                                        const SurfaceOptions& surface,
                                                        const char* role);

/// A path keyword (`output=`, `fit=`) taken as any object: a str or os.PathLike, or None
/// (nullopt). \throw pybind11::type_error in one line, "analyse(): output must be a str,
/// os.PathLike or None, not float" (pybind11's own refusal lists every signature).
[[nodiscard]] std::optional<std::filesystem::path> path_argument(const pybind11::object& value,
                                                                 const char* function,
                                                                 const char* keyword);

/// A bool keyword (`register=`) taken as any object: True or False only (not 1, not "yes").
/// \throw pybind11::type_error in one line.
[[nodiscard]] bool bool_argument(const pybind11::object& value, const char* function,
                                 const char* keyword);

void bind_mesh(pybind11::module_& m);
void bind_analysis(pybind11::module_& m);
void bind_asymmetry(pybind11::module_& m);

/// The types a mesh argument takes, as signatures and docstrings name them.
#define GLINT_MESH_LIKE_TYPES                                                 \
    "glint.Mesh | str | os.PathLike | tuple[numpy.ndarray, numpy.ndarray] | " \
    "open3d.geometry.TriangleMesh | trimesh.Trimesh | pyvista.PolyData"

}  // namespace glint::python

namespace pybind11::detail {

/// Takes any object (mesh_argument checks it); names the accepted types in signatures.
template <>
struct type_caster<glint::python::MeshLike> {
    PYBIND11_TYPE_CASTER(glint::python::MeshLike, const_name(GLINT_MESH_LIKE_TYPES));
    bool load(handle source, bool /*convert*/) {
        value.value = reinterpret_borrow<object>(source);
        return true;
    }
    static handle cast(const glint::python::MeshLike& mesh, return_value_policy, handle) {
        return mesh.value.inc_ref();
    }
};

}  // namespace pybind11::detail
