"""Fixtures of the glint Python tests: the module from the build folder (PYTHONPATH, set by
CTest), phantom pairs made with the glint command line (GLINT_EXE), the loader fixtures."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest


def _env_path(name):
    value = os.environ.get(name)
    if not value:
        pytest.skip(f"{name} is not set (run through ctest, which sets it)")
    return pathlib.Path(value)


@pytest.fixture(scope="session")
def glint_exe():
    return _env_path("GLINT_EXE")


@pytest.fixture(scope="session")
def test_data():
    return _env_path("GLINT_TEST_DATA_DIR")


def phantom(glint_exe, out, *args):
    """Runs `glint phantom ARGS -o OUT` and returns (path, sidecar dict)."""
    subprocess.run([str(glint_exe), "--quiet", "phantom", *args, "-o", str(out)], check=True)
    return out, json.loads(pathlib.Path(str(out) + ".json").read_text())


@pytest.fixture(scope="session")
def dent_pair(glint_exe, tmp_path_factory):
    """The condyle phantom (20 × 10 × 15 mm; a sphere would leave the rotation unobservable)
    and a re-tessellated copy with a 0.6 mm dent of radius 3 mm on its top at DENT_CENTER,
    moved by a known rigid pose. Returns (reference, examined, examined sidecar)."""
    folder = tmp_path_factory.mktemp("pair")
    ref, _ = phantom(glint_exe, folder / "ref.ply", "condyle", "--scheme", "ico", "--resolution", "4")
    exa, truth = phantom(glint_exe, folder / "exa.ply", "condyle", "--scheme", "uv", "--resolution", "48",
                         "--damage", "dent:center=2,-1,8.8 radius=3 depth=0.6", "--pose", "4,-3,5,0.3,-0.2,0.1")
    return ref, exa, truth


DENT_CENTER = np.array([2.0, -1.0, 8.8])


def world_from_phantom(truth):
    """The examined phantom's pose as a 4×4 matrix (its sidecar's world_from_phantom)."""
    return np.array(truth["world_from_phantom"], dtype=float)


# Small sweeps: a few views at 64 px keep each analysis near a second on two cores.
SMALL_SWEEP = dict(size=64, azimuth_step=60.0, elevations=[-45.0, 0.0, 45.0], views=False, exr=False)
