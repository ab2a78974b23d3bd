"""glint.load and glint.Mesh: numpy views without copies, errors as exceptions."""
import gc
import subprocess

import numpy as np
import pytest

import glint


def test_version_matches_command_line(glint_exe):
    out = subprocess.run([str(glint_exe), "--version"], check=True, capture_output=True, text=True).stdout
    assert out.strip() == f"glint {glint.__version__}"


def test_load_gives_typed_arrays(test_data):
    mesh = glint.load(test_data / "cube.obj")
    assert mesh.positions.shape == (8, 3) and mesh.positions.dtype == np.float32
    assert mesh.triangles.shape == (12, 3) and mesh.triangles.dtype == np.uint32
    assert mesh.normals.shape == (8, 3) and mesh.normals.dtype == np.float32
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-6)
    assert mesh.triangles.max() == 7
    assert mesh.vertex_count == 8 and mesh.triangle_count == 12
    assert mesh.report["format"] == "obj"
    assert mesh.unit is None  # cube.obj states no unit


def test_arrays_are_views_of_the_mesh(test_data):
    mesh = glint.load(str(test_data / "cube.obj"))
    a, b = mesh.positions, mesh.positions
    assert a.base is mesh  # the mesh owns the memory: no copy
    assert np.shares_memory(a, b)
    assert not a.flags.writeable
    with pytest.raises(ValueError):
        a[0, 0] = 1.0


def test_a_view_keeps_its_mesh_alive(test_data):
    positions = glint.load(test_data / "cube.obj").positions
    gc.collect()
    assert positions.shape == (8, 3)
    assert np.isfinite(positions).all() and positions.max() == pytest.approx(1.0)


def test_unit_stated_in_the_file(test_data):
    assert glint.load(test_data / "cube_m.obj").unit == "m"


def test_mesh_from_arrays_computes_normals():
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    mesh = glint.Mesh(positions, triangles, unit="mm")
    assert mesh.positions.dtype == np.float32 and mesh.unit == "mm"
    # The corner at the origin: its normal points away from the tetrahedron.
    assert (mesh.normals[0] < 0).all()
    assert mesh.report is None and mesh.source == "arrays"


def test_mesh_from_arrays_rejects_a_vertex_out_of_range():
    with pytest.raises(glint.InputError, match="triangle 1 uses vertex 9, mesh has 3 vertices"):
        glint.Mesh(np.eye(3), [[0, 1, 2], [0, 1, 9]])


def test_mesh_from_arrays_names_a_huge_unsigned_index_as_it_is():
    # Issue 52: a uint64 index 2^63+1 was printed negative.
    with pytest.raises(glint.InputError, match="triangle 1 uses vertex 9223372036854775809, mesh has 3 vertices"):
        glint.Mesh(np.eye(3), np.array([[0, 1, 2], [0, 1, 2**63 + 1]], dtype=np.uint64))


def test_mesh_from_arrays_refuses_float_indices():
    # Issue 23 item 15: 1.7 was truncated to vertex 1 without a word.
    with pytest.raises(glint.InputError, match="triangles must be an array of integers.*float64"):
        glint.Mesh(np.eye(3), [[0, 1.7, 2]])


def test_mesh_from_arrays_refuses_an_unknown_unit():
    # Issue 23 item 15: unit='parsec' was kept, and every later conversion was wrong.
    with pytest.raises(glint.InputError, match="unit 'parsec' is no length unit glint knows"):
        glint.Mesh(np.eye(3), [[0, 1, 2]], unit="parsec")
    assert glint.Mesh(np.eye(3), [[0, 1, 2]], unit="millimetre").unit == "mm"


def test_mesh_from_arrays_rejects_a_wrong_shape():
    with pytest.raises(glint.InputError, match=r"positions must be an N×3 array, found shape \(3, 2\)"):
        glint.Mesh(np.zeros((3, 2)), [[0, 1, 2]])


def test_missing_file_is_an_input_error_naming_it(tmp_path):
    missing = tmp_path / "no_such.ply"
    with pytest.raises(glint.InputError) as caught:
        glint.load(missing)
    assert isinstance(caught.value, ValueError) and isinstance(caught.value, glint.Error)
    assert "no_such.ply" in str(caught.value) and "\n" not in str(caught.value)


def test_malformed_file_is_an_input_error_naming_it(tmp_path):
    bad = tmp_path / "bad.ply"
    bad.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n")
    with pytest.raises(glint.InputError, match="bad.ply"):
        glint.load(bad)


def test_unwritable_save_is_an_io_error(test_data, tmp_path):
    mesh = glint.load(test_data / "cube.obj")
    with pytest.raises(glint.IoError) as caught:
        mesh.save(tmp_path / "no" / "such" / "cube.ply")
    assert isinstance(caught.value, OSError)


def test_save_and_load_round_trip(test_data, tmp_path):
    mesh = glint.load(test_data / "cube.obj")
    mesh.save(tmp_path / "cube.ply")
    again = glint.load(tmp_path / "cube.ply")
    np.testing.assert_array_equal(np.sort(again.positions, axis=0), np.sort(mesh.positions, axis=0))


def test_unknown_keyword_names_the_accepted_ones(test_data):
    with pytest.raises(TypeError, match="load\\(\\) got an unexpected keyword argument 'isovalue'; it takes: iso,"):
        glint.load(test_data / "cube.obj", isovalue=3)


def test_keyword_of_the_wrong_type_is_an_input_error(test_data):
    with pytest.raises(glint.InputError, match="load: iso = 'high': expected a number"):
        glint.load(test_data / "cube.obj", iso="high")


def test_surface_keywords_on_a_mesh_file_are_refused(test_data):
    with pytest.raises(glint.InputError):
        glint.load(test_data / "cube.obj", smooth=5)


def test_path_of_the_wrong_type_is_a_type_error():
    with pytest.raises(TypeError):
        glint.load(42)


def test_a_truncated_dicom_file_is_an_input_error_not_a_crash(tmp_path):
    """Issue 23 item 6: GDCM asserted on this folder and killed the interpreter."""
    (tmp_path / "f").write_bytes(b"\x08\x00\x05\x00")
    with pytest.raises(glint.InputError, match='no DICOM series in it.*"f": 4 bytes'):
        glint.load(tmp_path, iso=100)
