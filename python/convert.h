// glint.Mesh to and from the Python ecosystem (python/mesh_convert.cpp), and the mesh's own
// copies: transformed, pickled (python/mesh_state.cpp).
#pragma once

#include "mesh/mesh.h"
#include "python/bindings.h"

#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>

namespace glint::python {

/// The unit of a mesh made in Python from arrays, or from Open3D's or PyVista's (which state
/// none): millimetres, the unit of CT-derived surfaces, so that an analysis writes the same
/// field names (shape_change_mm) whichever way its meshes came (issue 51). glint.Mesh takes
/// unit=None for a mesh whose unit is unknown.
inline constexpr const char* kArrayUnit = "mm";

/// How errors name the arrays of one mesh argument: "reference", "reference[0] (vertices)",
/// "reference[1] (triangles)".
struct ArrayLabels {
    std::string owner;
    std::string positions;
    std::string triangles;
};

/// A mesh from N×3 positions and M×3 vertex ids (anything numpy.asarray takes), checked as a
/// loaded mesh is (numbers, finite, integer ids in range), with vertex normals.
/// \throw InputError (a ValueError in Python) naming the array and what was found.
[[nodiscard]] Mesh mesh_from_arrays(pybind11::handle positions, pybind11::handle triangles,
                                    const ArrayLabels& labels);

/// A (V, F) tuple or list, or a mesh of another library (Open3D legacy or tensor, trimesh,
/// PyVista) as a glint.Mesh; nullopt when `value` is none of them.
[[nodiscard]] std::optional<std::shared_ptr<MeshHandle>> converted_mesh(pybind11::handle value,
                                                                        const std::string& role);

/// Mesh.to_numpy(), to_open3d(), to_pyvista(), to_trimesh() (`self` is the glint.Mesh).
[[nodiscard]] pybind11::tuple to_numpy(const pybind11::object& self);
[[nodiscard]] pybind11::object to_open3d(const pybind11::object& self);
[[nodiscard]] pybind11::object to_pyvista(const pybind11::object& self);
[[nodiscard]] pybind11::object to_trimesh(const pybind11::object& self);

/// Mesh.transform(): a new mesh moved by a 4×4 affine matrix or an (R, t) pair.
[[nodiscard]] std::shared_ptr<MeshHandle> transformed(const MeshHandle& mesh,
                                                      pybind11::handle transform);

/// Pickling: the mesh as a tuple of plain values and back (the load report is not kept).
[[nodiscard]] pybind11::tuple mesh_state(const pybind11::object& self);
[[nodiscard]] std::shared_ptr<MeshHandle> mesh_from_state(const pybind11::tuple& state);

}  // namespace glint::python
