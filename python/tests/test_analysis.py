"""glint.register and glint.analyse: the fit and its evidence, the atlas as arrays, regions and
the report as Python objects, the same numbers as the files glint writes."""
import json
import threading
import time

import numpy as np
import pytest

import glint
from conftest import DENT_CENTER, SMALL_SWEEP, world_from_phantom


def rotation_error_deg(a, b):
    """Angle of the rotation between two 3×3 rotations."""
    c = (np.trace(a.T @ b) - 1.0) / 2.0
    return np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))


def test_register_recovers_the_known_pose(dent_pair, tmp_path):
    ref, exa, truth = dent_pair
    fit = glint.register(ref, exa, output=tmp_path / "fit.json")
    # The examined phantom was moved by world_from_phantom; the fit maps it back.
    expected = np.linalg.inv(world_from_phantom(truth))
    assert fit.converged and fit.mode == "register"
    assert fit.matrix.shape == (4, 4)
    # note: 0.05° and 0.01 mm: the dent covers a few % of the sphere and the robust loss keeps
    # it out of the fit (the CLI's registration tests hold the same bounds).
    assert rotation_error_deg(fit.rotation, expected[:3, :3]) < 0.05
    np.testing.assert_allclose(fit.translation, expected[:3, 3], atol=0.01)
    assert 0 < fit.rms < 0.05 and fit.inlier_fraction > 0.8 and fit.overlap > 0.9
    assert isinstance(fit.iterations, int) and fit.iterations > 0
    assert fit.termination in ("parameter change", "cost change")
    saved = json.loads((tmp_path / "fit.json").read_text())
    assert saved == fit.to_dict()
    np.testing.assert_allclose(np.array(saved["reference_from_examined"]), fit.matrix, atol=1e-9)


def test_register_takes_mesh_objects(dent_pair):
    ref, exa, _ = dent_pair
    by_path = glint.register(ref, exa)
    by_mesh = glint.register(glint.load(ref), glint.load(exa))
    np.testing.assert_allclose(by_mesh.matrix, by_path.matrix, atol=1e-9)


def test_register_fits_the_scale_when_asked(dent_pair):
    """Issue 53: the examined phantom 1 % larger. A rigid fit measures the scale it leaves and
    warns; fit_scale=True fits it (its uncertainty given), and the motion still matches."""
    ref, exa, truth = dent_pair
    loaded = glint.load(exa)
    larger = glint.Mesh(np.asarray(loaded.positions) * 1.01, np.asarray(loaded.triangles), unit="mm")
    rigid = glint.register(ref, larger)
    assert rigid.scale == 1.0
    assert rigid.scale_trend == pytest.approx(1 / 1.01 - 1, abs=0.002)
    assert any("scale-like pattern" in w and "fit_scale=True" in w for w in rigid.warnings)
    fit = glint.register(ref, larger, fit_scale=True)
    assert fit.scale == pytest.approx(1 / 1.01, abs=0.001)
    assert 0 < fit.scale_uncertainty < 0.001
    assert fit.to_dict()["examined_scale"] == fit.scale
    assert not any("scale-like pattern" in w for w in fit.warnings)
    # reference = matrix · (scale · examined): the examined phantom's pose undone at its size.
    expected = np.linalg.inv(world_from_phantom(truth))
    assert rotation_error_deg(fit.rotation, expected[:3, :3]) < 0.05


@pytest.fixture(scope="module")
def analysis(dent_pair, tmp_path_factory):
    ref, exa, _ = dent_pair
    out = tmp_path_factory.mktemp("analysis") / "atlas"
    return glint.analyse(ref, exa, output=out, **SMALL_SWEEP), out


def test_analyse_finds_the_dent(analysis):
    result, _ = analysis
    regions = [r for r in result.regions if r["zoom"] == 0]
    assert len(regions) == 1
    dent = regions[0]
    assert dent["kind"] == "dent" and dent["peak_depth"] < 0
    # The dent lies where it was made on the reference (the pose was fitted away); 1 mm: a
    # third of its radius (the centroid of a dent on a curved top sits below its centre).
    assert np.linalg.norm(np.array(dent["centroid"]) - DENT_CENTER) < 1.0
    assert result.fit.converged


def shape_field(result):
    """The decision field's name: the signed shape change with the run's unit (shape_change_mm)."""
    return "shape_change_" + (result.report["unit"] or "units")


def test_atlas_fields_are_per_vertex_arrays(analysis, dent_pair):
    result, _ = analysis
    reference = glint.load(dent_pair[0])
    fields = result.fields
    shape = shape_field(result)
    unit = result.report["unit"] or "units"
    assert list(fields)[0] == shape  # the decision field first, as in every atlas file
    for name in (shape, "shape_tolerance_" + unit, "seen_z0", "angle_mean_deg_z0", "angle_max_deg_z0",
                 "missing_fraction_z0", "pixels_z0", "region_id_z0"):
        assert fields[name].shape == (reference.vertex_count,) and fields[name].dtype == np.float32, name
        assert np.isfinite(fields[name]).all(), f"{name}: unseen vertices hold 0, never NaN"
    np.testing.assert_array_equal(result.atlas.positions, reference.positions)
    region = fields["region_id_z0"]
    assert int((region > 0).sum()) == sum(r["vertices"] for r in result.regions if r["zoom"] == 0)
    # Inside the region the surface moved inward; far from it, it did not.
    assert fields[shape][region > 0].min() < -0.3
    far = np.linalg.norm(reference.positions - DENT_CENTER, axis=1) > 6
    assert np.abs(fields[shape][far]).max() < 0.05
    assert fields["seen_z0"].max() == 1.0
    unseen = fields["seen_z0"] == 0
    assert (fields["angle_mean_deg_z0"][unseen] == 0).all()


def test_report_is_report_json(analysis):
    result, out = analysis
    written = json.loads((out / "report.json").read_text())
    report = result.report
    # note: the report is made again after the run, so only the total time may differ.
    written.pop("timings_s"), report.pop("timings_s")
    assert report == written
    assert result.regions_csv == (out / "regions.csv").read_text()
    assert result.output == out


def test_report_regions_match_the_atlas(analysis):
    result, _ = analysis
    zoom = result.report["zooms"][0]
    assert zoom["regions"] == [{k: v for k, v in r.items() if k != "zoom"} for r in result.regions if r["zoom"] == 0]
    assert 0.9 < zoom["coverage"] <= 1.0


def test_no_pictures_loads_no_image_library(dent_pair, tmp_path):
    """pictures=False (issue 25): in a fresh process whose plugin folder holds no plugin, the
    analysis writes its atlas and report without any picture and never maps OpenImageIO."""
    import os
    import subprocess
    import sys

    ref, exa, _ = dent_pair
    empty = tmp_path / "no_plugins"
    empty.mkdir()
    out = tmp_path / "atlas"
    script = (
        "import glint, sys\n"
        f"glint.analyse({str(ref)!r}, {str(exa)!r}, output={str(out)!r}, pictures=False, "
        f"**{SMALL_SWEEP!r})\n"
        "maps = open('/proc/self/maps').read()\n"
        "sys.exit(3 if 'OpenImageIO' in maps or 'glint_image_io' in maps else 0)\n"
    )
    env = dict(os.environ, GLINT_PLUGIN_DIR=str(empty))
    run = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    written = {p.name for p in out.rglob("*")}
    assert {"atlas.ply", "atlas.vtp", "report.json", "report.html"} <= written
    assert not any(name.endswith(".png") for name in written), written
    assert json.loads((out / "report.json").read_text())["analysis"]["exports"]["pictures"] is False


def test_analyse_without_register_on_aligned_copies(dent_pair):
    ref = dent_pair[0]
    result = glint.analyse(ref, ref, register=False, **SMALL_SWEEP)
    assert result.regions == [] and result.fit.mode == "identity"
    assert result.output is None
    assert np.abs(result.fields[shape_field(result)]).max() < 1e-4


def test_analyse_from_a_fit_file(dent_pair, tmp_path):
    ref, exa, _ = dent_pair
    glint.register(ref, exa, output=tmp_path / "fit.json")
    result = glint.analyse(ref, exa, fit=tmp_path / "fit.json", **SMALL_SWEEP)
    assert result.fit.mode == "file" and result.fit.rms is None
    assert [r["kind"] for r in result.regions] == ["dent"]


def test_existing_output_is_refused_then_replaced_with_force(dent_pair, tmp_path):
    ref = dent_pair[0]
    (tmp_path / "atlas").mkdir()
    with pytest.raises(glint.InputError, match="exists; give force=True to replace it"):
        glint.analyse(ref, ref, register=False, output=tmp_path / "atlas", **SMALL_SWEEP)
    glint.analyse(ref, ref, register=False, output=tmp_path / "atlas", force=True, **SMALL_SWEEP)
    assert (tmp_path / "atlas" / "report.json").is_file()


def test_output_holding_the_inputs_is_refused_before_any_work(dent_pair, tmp_path):
    """Issue 23 item 1: output=<the inputs' folder>, force=True deleted the inputs."""
    d = tmp_path / "d"
    d.mkdir()
    (d / "ref.ply").write_bytes(dent_pair[0].read_bytes())
    (d / "notes.txt").write_text("precious")
    with pytest.raises(glint.InputError, match="contains the input"):
        glint.analyse(d / "ref.ply", d / "ref.ply", register=False, output=d, force=True,
                      **SMALL_SWEEP)
    assert (d / "ref.ply").read_bytes() == dent_pair[0].read_bytes()
    assert (d / "notes.txt").read_text() == "precious"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d"]


def test_invalid_option_names_its_key(dent_pair):
    ref = dent_pair[0]
    with pytest.raises(glint.InputError, match="size = 0"):
        glint.analyse(ref, ref, size=0)
    with pytest.raises(glint.InputError, match="metric"):
        glint.analyse(ref, ref, metric="hsv")
    with pytest.raises(TypeError, match="unexpected keyword argument 'sise'"):
        glint.analyse(ref, ref, sise=64)


def test_analyse_releases_the_gil(dent_pair):
    ref, exa, _ = dent_pair
    done = {}
    worker = threading.Thread(target=lambda: done.setdefault("result", glint.analyse(ref, exa, **SMALL_SWEEP)))
    worker.start()
    ticks = 0
    while worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    assert "result" in done
    # note: a call holding the GIL would let this thread tick only at its start and end.
    assert ticks > 20


def test_cancel_while_the_inputs_load_stops_the_whole_call(dent_pair):
    """Issue 52: glint.cancel() in the first seconds of analyse, while its inputs loaded, was
    cleared when the analysis began; the call then ran to its end."""
    ref, exa, _ = dent_pair
    ref = glint.load(ref)

    class CancelsWhileRead:  # a mesh of another library whose arrays are read as the call starts
        vertices = ref.positions

        @property
        def triangles(self):
            glint.cancel()
            return ref.triangles

    with pytest.raises(KeyboardInterrupt, match="SIGINT received: stopped"):
        glint.analyse(CancelsWhileRead(), exa, register=True, size=128, views=False, exr=False)
    assert glint.analyse(ref, ref, register=False, **SMALL_SWEEP).regions == []


def test_cancel_from_another_thread_raises_keyboard_interrupt(dent_pair):
    ref, exa, _ = dent_pair
    timer = threading.Timer(0.3, glint.cancel)
    timer.start()
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt, match="SIGINT received: stopped"):
        glint.analyse(ref, exa, size=256, azimuth_step=10.0, elevations=[-60, -30, 0, 30, 60], views=False, exr=False)
    timer.join()
    assert time.monotonic() - started < 30
    # The flag is cleared: the next call runs.
    assert glint.analyse(ref, ref, register=False, **SMALL_SWEEP).regions == []
