"""glint.Mesh among numpy, Open3D, trimesh and PyVista: meshes in from any of them, out to
each, copies, moves, pickles, every format glint writes, and messages in Python's words."""
import copy
import importlib.util
import inspect
import pickle
import pydoc
import re
import sys
import types
import warnings

import numpy as np
import pytest

import glint
from conftest import SMALL_SWEEP

# A tetrahedron with outward (counter-clockwise) triangles; the corner at the origin.
TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)


def has_module(name):
    return importlib.util.find_spec(name) is not None


def tetra():
    return glint.Mesh(TETRA_V, TETRA_F, unit="mm")


def assert_same_mesh(a, b):
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.triangles, b.triangles)
    np.testing.assert_array_equal(a.normals, b.normals)


# --- inputs -------------------------------------------------------------------------------


class FakeTrimesh:
    """Stands for trimesh.Trimesh: vertices, faces and a unit word."""

    def __init__(self, vertices, faces, units=None):
        self.vertices, self.faces, self.units = vertices, faces, units


class FakePolyData:
    """Stands for pyvista.PolyData: points and a flat face list [n, ids…, n, ids…]."""

    def __init__(self, points, faces):
        self.points, self.faces = points, faces


def flat_faces(triangles):
    return np.hstack([np.full((len(triangles), 1), 3), triangles]).ravel()


def test_register_takes_a_numpy_pair_and_an_open3d_mesh(dent_pair):
    o3d = pytest.importorskip("open3d", reason="open3d not installed (Debian: python3-open3d)")
    ref, exa, _ = dent_pair
    by_path = glint.register(ref, exa)
    examined = glint.load(exa)
    legacy = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(examined.positions.astype(float)),
                                       o3d.utility.Vector3iVector(examined.triangles.astype(np.int32)))
    by_objects = glint.register(glint.load(ref).to_numpy(), legacy)
    np.testing.assert_allclose(by_objects.matrix, by_path.matrix, atol=1e-9)


def test_analyse_takes_a_list_pair_and_records_what_made_it():
    result = glint.analyse([TETRA_V, TETRA_F], FakeTrimesh(TETRA_V, TETRA_F, "millimeters"),
                           register=False, **SMALL_SWEEP)
    inputs = {i["role"]: i for i in result.report["inputs"]}
    assert "arrays" in str(inputs["reference"]) and "FakeTrimesh" in str(inputs["examined"])
    assert result.regions == []


def test_open3d_legacy_and_tensor_meshes_convert_exactly():
    o3d = pytest.importorskip("open3d", reason="open3d not installed (Debian: python3-open3d)")
    mesh = tetra()
    legacy = mesh.to_open3d()
    assert isinstance(legacy, o3d.geometry.TriangleMesh)
    np.testing.assert_array_equal(np.asarray(legacy.vertices), TETRA_V)
    np.testing.assert_array_equal(np.asarray(legacy.triangles), TETRA_F)
    np.testing.assert_allclose(np.asarray(legacy.vertex_normals), mesh.normals, atol=1e-7)
    tensor = o3d.t.geometry.TriangleMesh.from_legacy(legacy)
    for other in (legacy, tensor):
        back = glint.as_mesh(other)
        np.testing.assert_array_equal(back.positions, mesh.positions)
        np.testing.assert_array_equal(back.triangles, mesh.triangles)
        assert back.source.startswith("open3d.")


def test_duck_typed_meshes_become_glint_meshes():
    mesh = tetra()
    for other in (FakeTrimesh(TETRA_V, TETRA_F), FakePolyData(TETRA_V, flat_faces(TETRA_F)),
                  (TETRA_V.astype(np.float32), TETRA_F.astype(np.uint32)), [TETRA_V, TETRA_F]):
        converted = glint.as_mesh(other)
        np.testing.assert_array_equal(converted.positions, mesh.positions)
        np.testing.assert_array_equal(converted.triangles, mesh.triangles)
        np.testing.assert_array_equal(converted.normals, mesh.normals)
    assert glint.as_mesh(mesh) is mesh
    assert glint.as_mesh(FakeTrimesh(TETRA_V, TETRA_F, "millimeters")).unit == "mm"
    assert glint.as_mesh(FakeTrimesh(TETRA_V, TETRA_F)).source.endswith("FakeTrimesh")


def test_meshes_made_in_python_are_in_millimetres_unless_told(dent_pair):
    """Issue 51: an Open3D mesh without unit= renamed the atlas field to shape_change_units.
    Meshes from arrays or another library default to mm (as help(glint.Mesh) says); unit=None
    keeps a mesh of unknown unit."""
    for other in (FakePolyData(TETRA_V, flat_faces(TETRA_F)), (TETRA_V, TETRA_F),
                  FakeTrimesh(TETRA_V, TETRA_F)):
        assert glint.as_mesh(other).unit == "mm"
    assert glint.Mesh(TETRA_V, TETRA_F).unit == "mm"
    assert glint.Mesh(TETRA_V, TETRA_F, unit=None).unit is None
    assert "\"mm\" unless given" in glint.Mesh.__init__.__doc__
    ref = glint.load(dent_pair[0])
    arrays = (np.array(ref.positions), np.array(ref.triangles))
    atlas = glint.analyse(arrays, arrays, register=False, **SMALL_SWEEP).atlas
    assert "shape_change_mm" in atlas.scalars


def test_pyvista_faces_that_are_not_triangles_are_refused():
    quad = FakePolyData(TETRA_V, np.array([4, 0, 1, 2, 3]))
    with pytest.raises(ValueError, match=r"examined\.faces holds faces that are not triangles.*triangulate"):
        glint.register(tetra(), quad)
    with pytest.raises(ValueError, match=r"mesh\.faces holds faces that are not triangles"):
        glint.as_mesh(FakePolyData(TETRA_V, np.array([3, 0, 1, 2, 3, 0, 1])))


@pytest.mark.parametrize("arrays, message", [
    ((np.zeros((4, 2)), TETRA_F), r"reference\[0\] \(vertices\) must be an N×3 array, found shape \(4, 2\)"),
    ((np.array([[0, 0, 0], [np.nan, 0, 0], [0, 1, 0], [0, 0, 1]]), TETRA_F),
     r"reference\[0\] \(vertices\) must be finite, found nan in row 1"),
    ((np.array([["a", "b", "c"]] * 4), TETRA_F), r"reference\[0\] \(vertices\) must be an N×3 array of numbers, found dtype <U1"),
    ((TETRA_V, TETRA_F.astype(float)), r"reference\[1\] \(triangles\) must be an array of integers \(vertex indices\), found dtype float64"),
    ((TETRA_V, TETRA_F[:, :2]), r"reference\[1\] \(triangles\) must be an M×3 array, found shape \(4, 2\)"),
    ((TETRA_V, TETRA_F + 1), r"reference: triangle 1 uses vertex 4, mesh has 4 vertices"),
    ((TETRA_V, TETRA_F, TETRA_F), r"reference: a sequence must be \(vertices, triangles\), found 3 items"),
])
def test_arrays_that_are_no_mesh_are_a_value_error_naming_the_argument(arrays, message):
    with pytest.raises(ValueError, match=message):
        glint.register(arrays, tetra())


def test_objects_that_are_no_mesh_are_a_type_error_naming_the_argument():
    with pytest.raises(TypeError, match="examined must be a glint.Mesh, a path, .*Open3D.*, not int"):
        glint.register(tetra(), 42)


def test_from_numpy_is_the_constructor():
    assert_same_mesh(glint.Mesh.from_numpy(TETRA_V, TETRA_F), glint.Mesh(TETRA_V, TETRA_F))
    with pytest.raises(ValueError, match="glint.Mesh: positions must be finite"):
        glint.Mesh.from_numpy(TETRA_V * np.inf, TETRA_F)


# --- outputs ------------------------------------------------------------------------------


def test_to_numpy_round_trips_exactly():
    mesh = tetra()
    v, f = mesh.to_numpy()
    assert v.dtype == np.float64 and f.dtype == np.int64 and v.flags.writeable
    np.testing.assert_array_equal(v, TETRA_V)
    np.testing.assert_array_equal(f, TETRA_F)
    v[0, 0] = 5.0  # a copy: the mesh keeps its own
    assert mesh.positions[0, 0] == 0.0
    assert_same_mesh(glint.Mesh(*mesh.to_numpy()), mesh)


def test_open3d_round_trip_gives_the_same_mesh(test_data):
    pytest.importorskip("open3d", reason="open3d not installed (Debian: python3-open3d)")
    mesh = glint.load(test_data / "cube.obj")
    assert_same_mesh(glint.as_mesh(mesh.to_open3d()), mesh)


def test_missing_library_is_an_import_error_naming_how_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "open3d", None)  # import open3d now raises ImportError
    with pytest.raises(ImportError, match="to_open3d\\(\\) needs the open3d module.*python3-open3d"):
        tetra().to_open3d()
    monkeypatch.setitem(sys.modules, "pyvista", None)
    with pytest.raises(ImportError, match="pip install pyvista"):
        tetra().to_pyvista()
    monkeypatch.setitem(sys.modules, "trimesh", None)
    with pytest.raises(ImportError, match="pip install trimesh"):
        tetra().to_trimesh()


def fake_module(name, class_name):
    """A module whose one class records how it was called (pyvista / trimesh are not in
    Debian 12: these stand for them)."""
    class Recorder:
        def __init__(self, *args, **kwargs):
            self.args, self.kwargs, self.point_data = args, kwargs, {}
    module = types.ModuleType(name)
    setattr(module, class_name, Recorder)
    return module


def test_to_pyvista_builds_polydata_with_flat_faces(monkeypatch):
    monkeypatch.setitem(sys.modules, "pyvista", fake_module("pyvista", "PolyData"))
    mesh = tetra()
    poly = mesh.to_pyvista()
    points, faces = poly.args
    np.testing.assert_array_equal(points, TETRA_V)
    np.testing.assert_array_equal(faces, flat_faces(TETRA_F))
    np.testing.assert_array_equal(poly.point_data["Normals"], mesh.normals)


def test_to_trimesh_keeps_vertices_faces_and_unit(monkeypatch):
    monkeypatch.setitem(sys.modules, "trimesh", fake_module("trimesh", "Trimesh"))
    out = tetra().to_trimesh()
    np.testing.assert_array_equal(out.kwargs["vertices"], TETRA_V)
    np.testing.assert_array_equal(out.kwargs["faces"], TETRA_F)
    assert out.kwargs["process"] is False and out.units == "mm"


@pytest.mark.skipif(not has_module("pyvista"), reason="pyvista not installed (not packaged in Debian 12)")
def test_real_pyvista_round_trip():
    mesh = tetra()
    assert_same_mesh(glint.as_mesh(mesh.to_pyvista()), mesh)


@pytest.mark.skipif(not has_module("trimesh"), reason="trimesh not installed (not packaged in Debian 12)")
def test_real_trimesh_round_trip():
    mesh = tetra()
    assert_same_mesh(glint.as_mesh(mesh.to_trimesh()), mesh)


# --- copies, moves, pickles ----------------------------------------------------------------


def test_copy_is_independent_and_equal():
    mesh = tetra()
    for other in (mesh.copy(), copy.copy(mesh), copy.deepcopy(mesh)):
        assert other is not mesh and not np.shares_memory(other.positions, mesh.positions)
        assert_same_mesh(other, mesh)
        assert other.unit == "mm"


def rotation_z(deg):
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def test_transform_returns_a_new_mesh_and_leaves_this_one():
    mesh = tetra()
    r, t = rotation_z(30), np.array([1.0, -2.0, 3.0])
    matrix = np.eye(4)
    matrix[:3, :3], matrix[:3, 3] = r, t
    moved = mesh.transform(matrix)
    np.testing.assert_allclose(moved.positions, TETRA_V @ r.T + t, atol=1e-6)
    np.testing.assert_allclose(moved.normals, mesh.normals @ r.T, atol=1e-6)
    np.testing.assert_array_equal(mesh.positions, TETRA_V)  # unchanged
    assert_same_mesh(mesh.transform((r, t)), moved)


def test_a_moved_file_is_no_longer_that_file(test_data):
    loaded = glint.load(test_data / "cube.obj")
    moved = loaded.transform(np.eye(4))
    assert moved.report is None and moved.source == f"{loaded.source}, transformed"
    assert loaded.copy().report == loaded.report


def test_a_mirror_keeps_the_triangles_facing_outward():
    mirrored = tetra().transform(np.diag([-1.0, 1.0, 1.0, 1.0]))
    # The corner at the origin still points away from the body, now at -x mirrored: (+, -, -).
    assert mirrored.normals[0, 0] > 0 and (mirrored.normals[0, 1:] < 0).all()


@pytest.mark.parametrize("transform, message", [
    (np.zeros((4, 4)), "last row must be 0 0 0 1"),
    (np.diag([1.0, 1.0, 0.0, 1.0]), "singular"),
    (np.eye(3), r"the matrix must be 4×4, found shape \(3, 3\)"),
    ((np.eye(3), [1, 2]), r"t must be 3×1, found shape \(2,\)"),
    (np.full((4, 4), np.nan), "must be finite"),
])
def test_transform_refuses_what_is_no_affine_map(transform, message):
    with pytest.raises(ValueError, match=message):
        tetra().transform(transform)


def test_pickle_round_trip_keeps_every_array(dent_pair):
    atlas = glint.analyse(dent_pair[0], dent_pair[0], register=False, **SMALL_SWEEP).atlas
    again = pickle.loads(pickle.dumps(atlas))
    assert_same_mesh(again, atlas)
    assert again.unit == atlas.unit and again.source == atlas.source
    assert list(again.scalars) == list(atlas.scalars)
    for name, values in atlas.scalars.items():
        np.testing.assert_array_equal(again.scalars[name], values)
    np.testing.assert_array_equal(again.colors, atlas.colors)


def test_unpickling_checks_the_state_as_a_file_is_checked():
    """Issue 52: a pickled Mesh with a triangle index changed to 4e9 was accepted, and
    .transform() then wrote past the vertices (a segfault that killed the interpreter)."""
    state = list(tetra().__getstate__())
    triangles = np.array(state[2], copy=True)
    triangles[1, 2] = 4_000_000_000
    bad = glint.Mesh.__new__(glint.Mesh)
    with pytest.raises(ValueError, match=r"triangle 1 .*4000000000.*4 vertices"):
        bad.__setstate__(tuple(state[:2] + [triangles] + state[3:]))
    positions = np.array(state[1], copy=True)
    positions[0, 0] = np.nan
    with pytest.raises(ValueError, match="not finite|non-finite|NaN|nan"):
        glint.Mesh.__new__(glint.Mesh).__setstate__(tuple(state[:1] + [positions] + state[2:]))
    with pytest.raises(ValueError, match="2 normals for 4 vertices"):
        glint.Mesh.__new__(glint.Mesh).__setstate__(
            tuple(state[:3] + [np.asarray(state[3])[:2]] + state[4:]))


# --- saving -------------------------------------------------------------------------------


@pytest.mark.parametrize("extension", [".ply", ".vtk", ".stl", ".obj", ".off"])
def test_save_and_load_round_trip_in_every_format(tmp_path, extension):
    mesh = tetra()
    path = tmp_path / f"tetra{extension}"
    mesh.save(path)
    again = glint.load(path)
    assert again.triangle_count == 4 and again.unit == "mm"
    key = lambda p: np.lexsort(p.T)  # noqa: E731 (STL and OBJ weld back in their own order)
    np.testing.assert_array_equal(again.positions[key(again.positions)], mesh.positions[key(mesh.positions)])


def test_save_vtp_is_read_by_vtk(tmp_path):
    """glint reads no VTP; VTK itself (python3-vtk9) is the reader that matters."""
    vtk = pytest.importorskip("vtk", reason="vtk not installed (Debian: python3-vtk9)")
    from vtk.util.numpy_support import vtk_to_numpy
    tetra().save(tmp_path / "tetra.vtp")
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(str(tmp_path / "tetra.vtp"))
    reader.Update()
    poly = reader.GetOutput()
    np.testing.assert_array_equal(vtk_to_numpy(poly.GetPoints().GetData()), TETRA_V)
    assert poly.GetNumberOfPolys() == 4


def test_save_refuses_an_unknown_extension_and_the_file_it_was_loaded_from(tmp_path):
    mesh = tetra()
    with pytest.raises(ValueError, match=r"unknown extension \".xyz\", expected .ply, .vtk, .vtp, .stl, .obj or .off"):
        mesh.save(tmp_path / "tetra.xyz")
    mesh.save(tmp_path / "input.obj")
    loaded = glint.load(tmp_path / "input.obj")
    with pytest.raises(glint.InputError, match="is the input"):
        loaded.save(tmp_path / "input.obj")


# --- Python's words -----------------------------------------------------------------------


def test_an_existing_output_names_the_force_keyword(dent_pair, tmp_path):
    (tmp_path / "atlas").mkdir()
    with pytest.raises(glint.InputError, match="exists; give force=True to replace it") as caught:
        glint.analyse(dent_pair[0], dent_pair[0], register=False, output=tmp_path / "atlas")
    assert "--" not in str(caught.value)


def test_warnings_are_python_warnings_and_stay_in_the_result(dent_pair):
    with pytest.warns(glint.GlintWarning, match=r"no fit requested \(fit=FILE or register=True\)"):
        result = glint.analyse(dent_pair[0], dent_pair[0], register=False, **SMALL_SWEEP)
    assert issubclass(glint.GlintWarning, UserWarning)
    assert any("no fit requested" in w for w in result.warnings)
    with warnings.catch_warnings():
        warnings.simplefilter("error", glint.GlintWarning)
        with pytest.raises(glint.GlintWarning):
            glint.analyse(dent_pair[0], dent_pair[0], register=False, **SMALL_SWEEP)


def test_load_warnings_are_python_warnings_and_stay_in_the_report(tmp_path):
    obj = tmp_path / "tetra.obj"
    obj.write_text("mtllib missing.mtl\n" + "".join(f"v {x} {y} {z}\n" for x, y, z in TETRA_V) +
                   "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in TETRA_F))
    for load in (glint.load, glint.as_mesh):
        with pytest.warns(glint.GlintWarning, match='material library "missing.mtl" not found'):
            mesh = load(obj)
        assert any("missing.mtl" in w for w in mesh.report["warnings"])


def test_help_shows_the_types_of_the_mesh_arguments_and_every_keyword():
    doc = glint.analyse.__doc__
    assert "reference, examined: glint.Mesh | str | os.PathLike | tuple[numpy.ndarray, numpy.ndarray]" in doc
    assert "handle" not in doc
    assert "size: int = " in doc and "[px]" in doc and "force: bool = False" in doc
    assert "examined: glint.Mesh | str" in glint.register.__doc__


@pytest.mark.parametrize("function", ["analyse", "register", "options"])
def test_the_signature_lists_every_keyword_with_its_default(function):
    # help(), IDEs and inspect read the signature, not **kwargs: every keyword the docstring
    # documents is a keyword-only parameter with the default the docstring states.
    fn = getattr(glint, function)
    signature = inspect.signature(fn)
    params = signature.parameters
    assert all(p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY) for p in params.values())
    documented = re.findall(r"^    (\w+): ", fn.__doc__, flags=re.M)
    assert documented and set(documented) <= set(params), set(documented) - set(params)
    for name in documented:
        line = re.search(rf"^    {name}: [^=—]*(?:= (.*?))?(?: \[[^\]]*\])? — ", fn.__doc__, flags=re.M)
        if line and line.group(1) and line.group(1) != "None":
            assert repr(params[name].default).replace('"', "'") == line.group(1), name
    if function == "analyse":
        assert params["size"].default == 512 or isinstance(params["size"].default, int)
        assert params["loss"].default == "cauchy"
        assert params["register"].default is True and params["force"].default is False
        assert "analyse(reference, examined, *, register=True" in pydoc.render_doc(fn, renderer=pydoc.plaintext)


def test_a_rule_between_options_names_the_keyword():
    # The rule is checked once all options are set (the metric bounds the threshold); the
    # library names the option by its scenario key, threshold.deg: Python by its keyword.
    with pytest.raises(glint.InputError, match=r"^threshold_deg = 250: must be in \(0, 180\] deg"):
        glint.options(threshold_deg=250, metric="angle")


def test_help_writes_defaults_as_python_literals():
    doc = glint.analyse.__doc__
    assert "coarse: bool = True" in doc and "symmetric: bool = False" in doc
    assert "loss: str = 'cauchy'" in doc
    assert "elevations: sequence of float = [-60, -30, 0, 30, 60] [deg]" in doc
    assert "unit: str = None" in doc
