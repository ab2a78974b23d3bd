"""glint.asymmetry(): one surface against its own mirror image (issue 27), on phantoms made here
with numpy: an ellipsoid bent so that x = 0 is its only mirror plane (with and without a dent
on +x), and the same ellipsoid twisted about z, which has no mirror plane at all."""
import inspect

import numpy as np
import pytest

import glint
from conftest import SMALL_SWEEP

RADII = np.array([15.0, 9.0, 6.0])  # mm: the size of the condyle phantom the sweeps are made for
DENT_CENTER = RADII * np.array([np.sin(np.pi / 3) * np.cos(np.pi / 6),
                                np.sin(np.pi / 3) * np.sin(np.pi / 6), np.cos(np.pi / 3)])
DENT_RADIUS, DENT_DEPTH = 3.0, 0.6  # mm, as the condyle dent of test_analysis.py


def ellipsoid(rings=48, segments=96):
    """A closed UV ellipsoid (outward winding) with RADII; `segments` even, so that the grid
    itself is mirror-symmetric about x = 0."""
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    t, p = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1).reshape(-1, 3)
    vertices = np.vstack([[0, 0, 1], ring, [0, 0, -1]]) * RADII
    bottom = len(vertices) - 1
    idx = lambda r, s: 1 + r * segments + s % segments  # noqa: E731
    tris = []
    for s in range(segments):
        tris.append([0, idx(0, s), idx(0, s + 1)])
        tris.append([bottom, idx(rings - 2, s + 1), idx(rings - 2, s)])
        for r in range(rings - 2):
            a, b, c, d = idx(r, s), idx(r, s + 1), idx(r + 1, s), idx(r + 1, s + 1)
            tris += [[a, c, b], [b, c, d]]
    return vertices, np.array(tris, dtype=np.int64)


def one_plane_shape(dent=False):
    """The ellipsoid bent so that x = 0 is its only mirror plane; with `dent`, a cosine dent
    (radius DENT_RADIUS, depth DENT_DEPTH, towards the centre) on the +x side."""
    v, f = ellipsoid()
    if dent:
        d = np.linalg.norm(v - DENT_CENTER, axis=1)
        depth = np.where(d < DENT_RADIUS, DENT_DEPTH * 0.5 * (1 + np.cos(np.pi * d / DENT_RADIUS)), 0.0)
        v = v * (1 - depth / np.linalg.norm(v, axis=1))[:, None]
    x, y, z = v.T
    return np.stack([x * (1 + 0.25 * z / RADII[2]), y + 0.02 * x * x, z], axis=1), f


def chiral_shape():
    """The ellipsoid twisted about z by 60° from bottom to top: no mirror plane."""
    v, f = ellipsoid()
    a = v[:, 2] / RADII[2] * np.pi / 3
    x, y = v[:, 0], v[:, 1]
    return np.stack([x * np.cos(a) - y * np.sin(a), x * np.sin(a) + y * np.cos(a), v[:, 2]], axis=1), f


def test_signature_is_inspectable():
    params = inspect.signature(glint.asymmetry).parameters
    assert list(params)[:4] == ["mesh", "plane", "fit_roi", "output"]
    assert params["plane"].kind is inspect.Parameter.KEYWORD_ONLY
    assert "keywords" in params


def test_symmetric_shape_has_its_plane_and_no_finding():
    result = glint.asymmetry(one_plane_shape(), unit="mm", **SMALL_SWEEP)
    plane = result.plane
    assert plane["plausible"], plane["verdict"]
    assert abs(plane["normal"][0]) > 0.999  # within 2.6° of the x axis
    assert abs(plane["point"] @ plane["normal"]) < 0.1  # mm from x = 0
    assert result.findings == []
    assert result.field.shape == (len(one_plane_shape()[0]),)
    assert result.output is None


def test_one_sided_dent_is_one_finding_on_its_side(tmp_path):
    vertices, triangles = one_plane_shape(dent=True)
    result = glint.asymmetry((vertices, triangles), plane="x=0", unit="mm",
                             output=tmp_path / "asym", **SMALL_SWEEP)
    assert result.plane["source"] == "given"
    assert len(result.findings) == 1, result.findings
    finding = result.findings[0]
    assert finding["side"] == "+x"
    assert finding["side_direction"][0] > 0.99
    assert finding["kind"] == "less"
    assert -0.8 < finding["depth"] < -0.3  # mm; the dent is 0.6 deep, sampled by the sweep
    assert finding["area"] > 0 and finding["volume"] < 0
    assert finding["sentence"].startswith("+x side: 0."), finding["sentence"]
    # The field is this side minus the mirrored other: most negative inside the dent.
    inside = np.linalg.norm(vertices - _bent(DENT_CENTER), axis=1) < 1.5
    assert result.field[inside].min() < -0.3
    assert result.output == tmp_path / "asym"
    report = result.report["asymmetry"]
    assert report["findings"][0]["kind"] == "less"
    # The smallest one-sided change the run can tell, as report.json states it: the dent
    # (0.6 deep) stands above it.
    floor = result.symmetry_floor
    assert 0 < floor["min_detectable_depth"] < 0.6, floor
    assert floor["min_detectable_area"] > 0
    assert floor["min_detectable_depth"] == pytest.approx(
        report["symmetry_floor"]["min_detectable_depth"])
    assert (tmp_path / "asym" / "report.json").exists()


def _bent(p):
    x, y, z = p
    return np.array([x * (1 + 0.25 * z / RADII[2]), y + 0.02 * x * x, z])


def test_no_plausible_plane_raises_with_the_best_plane():
    with pytest.raises(glint.Error, match=r"no plausible symmetry plane.*plane='point="):
        glint.asymmetry(chiral_shape(), unit="mm", **SMALL_SWEEP)


def test_bad_plane_text_names_the_keyword():
    with pytest.raises(glint.InputError, match=r"^plane='w=3': expected x=C"):
        glint.asymmetry(one_plane_shape(), plane="w=3")


def test_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError, match="asymmetry"):
        glint.asymmetry(one_plane_shape(), no_such_keyword=1)


def test_fit_roi_is_checked_and_named():
    with pytest.raises(glint.InputError, match=r"fit_roi: ROI 'sphere:1,2'"):
        glint.asymmetry(one_plane_shape(), fit_roi="sphere:1,2")
    with pytest.raises(glint.InputError, match=r"ROI sphere:100,100,100,1 contains no vertex"):
        glint.asymmetry(one_plane_shape(), fit_roi="sphere:100,100,100,1")
