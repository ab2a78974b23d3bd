"""Seeded hostile cases for the Python module's entry points (issue 23: "fuzz … the Python entry
points"), run by test_entry_points_fuzz.py in a child interpreter so that a crash is seen.

    python3 entry_point_cases.py SEED WORKDIR GLINT_EXE TEST_DATA

Writes one JSON line per case to stdout: {"case", "call", "outcome": "ok" | "raised", "type",
"message"}; before each case a {"start": case} line, flushed, so that a child that dies names
the case it died in.
"""
import json
import math
import pathlib
import random
import re
import subprocess
import sys

import numpy as np

import glint

HOSTILE_NUMBERS = [
    "nan", "-nan", "inf", "-inf", "1e308", "-1e308", "1e-320", "-1", "0", "4294967296",
    "18446744073709551617", "99999999999", "0x10", "1e", "--1", "",
]
HOSTILE_VALUES = [
    math.nan, math.inf, -math.inf, -1, 0, 1e308, -1e-300, 2**64 + 1, 2**31, 3.5, "", "nan",
    "\x1b[31mred\x07", b"bytes", None, [], [math.nan], {}, True, "x" * 5000, "/dev/zero",
]


def mutate(data: bytes, rng: random.Random) -> bytes:
    """One hostile change: a cut, flipped bytes, a spliced copy, or numbers turned hostile."""
    kind = rng.randrange(5)
    if kind == 0 and data:
        return data[: rng.randrange(len(data))]
    if kind == 1 and data:
        out = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            out[rng.randrange(len(out))] = rng.randrange(256)
        return bytes(out)
    if kind == 2 and data:
        a, b = sorted(rng.randrange(len(data)) for _ in range(2))
        at = rng.randrange(len(data))
        return data[:at] + data[a:b] * rng.randint(1, 4) + data[at:]
    if kind == 3:
        def swap(match):
            return rng.choice(HOSTILE_NUMBERS).encode() if rng.random() < 0.2 else match.group(0)
        return re.sub(rb"-?\d+(\.\d+)?(e-?\d+)?", swap, data)
    lines = data.split(b"\n")
    if len(lines) > 2:
        i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    return b"\n".join(lines)


def seed_files(work: pathlib.Path, glint_exe: str, test_data: pathlib.Path):
    """Small valid inputs of every kind the module reads."""
    seeds = {"cube.obj": (test_data / "cube.obj").read_bytes()}
    for name in ("ref.ply", "ref.stl", "ref.off", "ref.vtk"):
        path = work / name
        subprocess.run([glint_exe, "--quiet", "phantom", "sphere", "--resolution", "1", "-o",
                        str(path)], check=True, stdout=subprocess.DEVNULL)
        seeds[name] = path.read_bytes()
    header = (b"ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_SHORT\n"
              b"ElementSpacing = 1 1 1\nElementDataFile = LOCAL\n")
    seeds["vol.mha"] = header + np.arange(64, dtype="<i2").tobytes()
    seeds["fit.json"] = json.dumps({"matrix": np.eye(4).tolist()}).encode()
    return seeds


class Runner:
    def __init__(self):
        self.case = 0

    def run(self, call: str, fn):
        self.case += 1
        print(json.dumps({"start": self.case}), flush=True)
        record = {"case": self.case, "call": call[:300]}
        try:
            fn()
            record["outcome"] = "ok"
        except BaseException as e:  # noqa: B902 - every kind is recorded and judged by the test
            record.update(outcome="raised", type=type(e).__name__,
                          glint_error=isinstance(e, glint.Error), message=str(e)[:2000])
        print(json.dumps(record), flush=True)


def file_cases(runner, rng, work, seeds):
    for name, data in seeds.items():
        for n in range(25):
            path = work / f"m{n}_{name}"
            path.write_bytes(mutate(data, rng))
            kwargs = {"iso": rng.choice([0.5, 30.0, math.nan, -1e30])} if name.endswith(".mha") else {}
            runner.run(f"load(mutated {name} #{n}, {kwargs})", lambda p=path, k=kwargs: glint.load(p, **k))


def argument_cases(runner, rng, work, seeds):
    good = work / "good.ply"
    good.write_bytes(seeds["ref.ply"])
    mesh = glint.load(good)
    load_keys = ["iso", "surface_roi", "largest", "seed", "smooth", "passband", "edge", "tolerance",
                 "unit", "no_such_keyword"]
    option_keys = ["unit", "loss", "samples", "max_iterations", "azimuth_step", "elevations",
                   "zoom", "roi", "size", "margin", "supersample", "metric", "backend", "device",
                   "max_incidence", "min_coverage", "rule", "threshold_deg", "noise_k",
                   "min_threshold_deg", "min_region_vertices", "max_plausible_deg",
                   "grow_fraction", "atlas_formats", "mosaic_tile", "up", "plan", "fit_seed"]
    for _ in range(60):
        key, value = rng.choice(load_keys), rng.choice(HOSTILE_VALUES)
        runner.run(f"load(good.ply, {key}={value!r:.60})", lambda k=key, v=value: glint.load(good, **{k: v}))
    for _ in range(150):
        kwargs = {rng.choice(option_keys): rng.choice(HOSTILE_VALUES) for _ in range(rng.randint(1, 3))}
        runner.run(f"options({kwargs!r:.200})", lambda k=kwargs: glint.options(**k))
    positions = np.asarray(mesh.positions)
    triangles = np.asarray(mesh.triangles)
    arrays = [
        (positions, triangles.astype(np.float64) + 0.5),
        (positions, triangles.astype(np.int64) - 1),
        (positions, triangles.astype(np.int64) + len(positions)),
        (np.full_like(positions, np.nan), triangles),
        (positions * 1e300, triangles),
        (positions[:, :2], triangles),
        (positions, triangles[:, :2]),
        (positions[:0], triangles[:0]),
        (positions.astype(object), triangles),
        (positions, np.array([[2**40, 0, 1]])),
    ]
    for n, pair in enumerate(arrays):
        runner.run(f"as_mesh(arrays #{n})", lambda p=pair: glint.as_mesh(p))
    matrices = [np.full((4, 4), np.nan), np.zeros((4, 4)), np.eye(3), np.eye(4) * 1e308,
                (np.eye(3), [math.inf, 0, 0]), "eye", np.eye(4)[:, :3], [[1, 2], [3]]]
    for n, m in enumerate(matrices):
        runner.run(f"Mesh.transform(#{n})", lambda t=m: mesh.transform(t))
    planes = [math.nan, "x=nan", "x=1e309", "point=0,0,0;normal=0,0,0", "landmarks=1,2,3", "",
              "y", "x=0;x=1", "\x1b[2J"]
    for plane in planes:
        runner.run(f"asymmetry(good.ply, plane={plane!r})",
                   lambda p=plane: glint.asymmetry(mesh, plane=p, size=32, azimuth_step=90,
                                                   elevations=[0]))
    register_keys = ["loss", "samples", "max_iterations", "fit_seed", "unit", "fit_roi", "coarse"]
    for _ in range(10):
        key, value = rng.choice(register_keys), rng.choice(HOSTILE_VALUES)
        runner.run(f"register(good, good, {key}={value!r:.60})",
                   lambda k=key, v=value: glint.register(mesh, mesh, **{k: v}))
    for target in [work / "missing.json", good, work, "/dev/zero"]:
        runner.run(f"analyse(good, good, fit={target})",
                   lambda f=target: glint.analyse(mesh, mesh, fit=str(f), size=32))


def main():
    seed, work, glint_exe, test_data = int(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3], \
        pathlib.Path(sys.argv[4])
    work.mkdir(parents=True, exist_ok=True)
    rng = random.Random(seed)
    seeds = seed_files(work, glint_exe, test_data)
    runner = Runner()
    file_cases(runner, rng, work, seeds)
    argument_cases(runner, rng, work, seeds)
    sys.stdout.flush()


if __name__ == "__main__":
    main()
