// glint.Mesh.transform() and pickling: new meshes from a mesh, never changes to one (its
// numpy views are read-only and may be held elsewhere; an in-place move would change them
// under their holders).
#include "python/convert.h"

#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/validate.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <utility>

namespace py = pybind11;

namespace glint::python {

namespace {

std::string text_of(py::handle value) { return py::cast<std::string>(py::str(value)); }

// A numpy array of `rows` × `cols` doubles, or InputError naming what it is.
Eigen::MatrixXd matrix_of(py::handle value, long rows, long cols, const std::string& what) {
    const py::array a = py::module_::import("numpy").attr("asarray")(value, "float64");
    const bool vector = cols == 1 && a.ndim() == 1 && a.shape(0) == rows;
    if (!vector && !(a.ndim() == 2 && a.shape(0) == rows && a.shape(1) == cols))
        throw InputError("transform: " + what + " must be " + std::to_string(rows) + "×" +
                         std::to_string(cols) + ", found shape " +
                         text_of(py::repr(a.attr("shape"))));
    Eigen::MatrixXd m = py::cast<Eigen::MatrixXd>(a.attr("reshape")(rows, cols));
    if (!m.allFinite()) throw InputError("transform: " + what + " must be finite");
    return m;
}

// The 4×4 affine matrix of a transform argument: a matrix, or a pair (R, t).
Eigen::Matrix4d affine_of(py::handle transform) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (py::isinstance<py::tuple>(transform) || py::isinstance<py::list>(transform)) {
        const auto pair = py::reinterpret_borrow<py::sequence>(transform);
        if (pair.size() != 2)
            throw InputError(
                "transform: expected a 4×4 matrix or a pair (R, t), found a "
                "sequence of " +
                std::to_string(pair.size()) + " items");
        m.topLeftCorner<3, 3>() = matrix_of(pair[0], 3, 3, "R");
        m.topRightCorner<3, 1>() = matrix_of(pair[1], 3, 1, "t");
        return m;
    }
    m = matrix_of(transform, 4, 4, "the matrix");
    if (m.row(3) != Eigen::RowVector4d(0, 0, 0, 1))
        throw InputError(
            "transform: the matrix's last row must be 0 0 0 1 (an affine map), found " +
            text_of(py::repr(py::cast(Eigen::RowVector4d(m.row(3))))));
    return m;
}

// Rows of three values (positions, triangles, colours) as an owning N×3 numpy array.
template <class Scalar, class Row>
py::array array_copy(const std::vector<Row>& rows) {
    static_assert(sizeof(Row) == 3 * sizeof(Scalar));
    py::array_t<Scalar> out({static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}});
    if (!rows.empty()) std::memcpy(out.mutable_data(), rows.data(), rows.size() * sizeof(Row));
    return out;
}

template <class Scalar, class Row>
void read_rows(const py::handle array, std::vector<Row>& into) {
    static_assert(sizeof(Row) == 3 * sizeof(Scalar));
    const auto a = py::array_t<Scalar, py::array::c_style | py::array::forcecast>::ensure(array);
    if (!a || a.ndim() != 2 || a.shape(1) != 3)
        throw InputError("glint.Mesh: a pickled state with an array of the wrong shape");
    into.resize(static_cast<std::size_t>(a.shape(0)));
    if (!into.empty())
        std::memcpy(static_cast<void*>(into.data()), a.data(), into.size() * sizeof(Row));
}

}  // namespace

std::shared_ptr<MeshHandle> transformed(const MeshHandle& mesh, py::handle transform) {
    const Eigen::Matrix4d m = affine_of(transform);
    const Eigen::Matrix3d linear = m.topLeftCorner<3, 3>();
    const double det = linear.determinant();
    if (!(std::fabs(det) > 1e-12 * std::pow(linear.norm(), 3)))
        throw InputError("transform: the matrix is singular (determinant " + std::to_string(det) +
                         "): it would flatten the mesh");
    auto out = std::make_shared<MeshHandle>(mesh);
    for (Vec3f& p : out->mesh.positions)
        p = (linear * p.cast<double>() + m.topRightCorner<3, 1>()).cast<float>();
    // A mirror turns the triangles inside out: their winding is reversed so that they are
    // counter-clockwise seen from outside again.
    if (det < 0)
        for (auto& t : out->mesh.triangles) std::swap(t[1], t[2]);
    compute_vertex_normals(out->mesh);  // normals follow any affine map once recomputed
    // No longer the file it was loaded from: report.json must not record that file as the
    // input.
    out->source = mesh.source + ", transformed";
    out->report.reset();
    out->surface.reset();
    return out;
}

py::tuple mesh_state(const py::object& self) {
    const MeshHandle& h = self.cast<const MeshHandle&>();
    const Mesh& x = h.mesh;
    py::list scalars;
    for (const ScalarField& f : x.scalars)
        scalars.append(py::make_tuple(
            f.name,
            py::array_t<float>(static_cast<py::ssize_t>(f.values.size()), f.values.data())));
    py::object colors = py::none(), labels = py::none();
    if (!x.colors.empty()) colors = array_copy<std::uint8_t>(x.colors);
    if (!x.labels.empty())
        labels =
            py::array_t<std::int32_t>(static_cast<py::ssize_t>(x.labels.size()), x.labels.data());
    return py::make_tuple(1, array_copy<float>(x.positions), array_copy<std::uint32_t>(x.triangles),
                          array_copy<float>(x.normals), colors, labels, scalars, x.unit, h.source);
}

std::shared_ptr<MeshHandle> mesh_from_state(const py::tuple& state) {
    if (state.size() != 9 || py::cast<int>(state[0]) != 1)
        throw InputError("glint.Mesh: a pickled state this version does not read");
    auto h = std::make_shared<MeshHandle>();
    Mesh& x = h->mesh;
    read_rows<float>(state[1], x.positions);
    read_rows<std::uint32_t>(state[2], x.triangles);
    read_rows<float>(state[3], x.normals);
    if (!state[4].is_none()) read_rows<std::uint8_t>(state[4], x.colors);
    if (!state[5].is_none()) x.labels = py::cast<std::vector<std::int32_t>>(state[5]);
    for (const py::handle item : py::cast<py::list>(state[6])) {
        const auto pair = py::cast<py::tuple>(item);
        x.scalars.push_back(
            {py::cast<std::string>(pair[0]), py::cast<std::vector<float>>(pair[1])});
    }
    x.unit = py::cast<std::string>(state[7]);
    h->source = py::cast<std::string>(state[8]);
    // A pickle is bytes from anywhere: a triangle index changed to 4e9 was accepted and
    // .transform() then wrote past the vertices (issue 52). The state is checked as a loaded
    // file is, and every per-vertex array must have one value per vertex.
    check_mesh(x, "glint.Mesh (unpickled)");
    const std::size_t n = x.vertex_count();
    const auto per_vertex = [&](std::size_t size, const std::string& what) {
        if (size != 0 && size != n)
            throw InputError("glint.Mesh (unpickled): " + std::to_string(size) + " " + what +
                             " for " + std::to_string(n) + " vertices; expected one per vertex");
    };
    per_vertex(x.normals.size(), "normals");
    per_vertex(x.colors.size(), "colours");
    per_vertex(x.labels.size(), "labels");
    for (const ScalarField& f : x.scalars)
        per_vertex(f.values.size(), "values of '" + f.name + "'");
    if (x.normals.empty()) compute_vertex_normals(x);
    return h;
}

}  // namespace glint::python
