"""Hostile input to the module's public entry points (issue 23: fuzz the Python entry points).

Seeded random mutations of small valid inputs (meshes in PLY, OBJ, STL and OFF, a MetaImage
volume, a scenario .toml, a fit .json) and hostile argument values (NaN, inf, negative, huge,
wrong types, empty strings, ESC bytes, folders, FIFOs) go to glint.load, as_mesh, Mesh,
Mesh.transform, register, analyse, asymmetry and options. The cases run one after another in a
worker process, so that a crash (a signal) or a hang (a timeout) is caught and names its case;
a worker that dies is replaced. Every case must succeed or raise an exception whose message is
one line. The seed is fixed: a failure reproduces."""
import base64
import math
import os
import pathlib
import pickle
import random
import select
import subprocess
import sys

import numpy as np
import pytest

SEED = 23
CASE_TIMEOUT_S = 20.0
# note: a run past this is a hang; the worker is killed and the case reported.

WORKER = r"""
import base64, pickle, sys, warnings
import numpy as np
import glint
warnings.simplefilter("ignore")

class Opaque:  # an argument of no type glint knows
    pass

def value(v):
    if isinstance(v, tuple) and v[:1] == ("array",):
        return np.array(v[1], dtype=v[2])
    if isinstance(v, tuple) and v[:1] == ("pair",):
        return (value(v[1]), value(v[2]))
    return Opaque() if v == "<opaque>" else v

for line in sys.stdin:
    entry, args, kwargs = pickle.loads(base64.b64decode(line))
    args = [value(a) for a in args]
    kwargs = {k: value(v) for k, v in kwargs.items()}
    try:
        if entry == "transform":
            glint.load(args[0]).transform(args[1])
        elif entry == "Mesh":
            glint.Mesh(*args, **kwargs)
        else:
            getattr(glint, entry)(*args, **kwargs)
        result = ("ok", "", "")
    except Exception as e:  # every exception is an answer; its message is checked
        result = ("raised", type(e).__name__, str(e))
    sys.stdout.write(base64.b64encode(pickle.dumps(result)).decode() + "\n")
    sys.stdout.flush()
"""


def sphere_mesh(subdivisions=2):
    """An icosphere of radius 10 (320 triangles): small, closed, and not symmetric enough to
    make every fit degenerate once mutated."""
    t = (1.0 + 5 ** 0.5) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [np.array(p, float) / np.linalg.norm(p) for p in v]
    for _ in range(subdivisions):
        cache, faces = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = verts[a] + verts[b]
                verts.append(m / np.linalg.norm(m))
                cache[key] = len(verts) - 1
            return cache[key]

        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = faces
    return np.array(verts) * 10.0, np.array(f)


def mesh_texts(positions, triangles):
    """The mesh as the text of each format's file (binary STL aside, covered by fuzz/)."""
    vs = "".join(f"{x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in positions)
    ply = (f"ply\nformat ascii 1.0\nelement vertex {len(positions)}\nproperty float x\n"
           f"property float y\nproperty float z\nelement face {len(triangles)}\n"
           "property list uchar int vertex_indices\nend_header\n" + vs +
           "".join(f"3 {a} {b} {c}\n" for a, b, c in triangles))
    obj = "".join(f"v {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in positions) + "".join(
        f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles)
    off = f"OFF\n{len(positions)} {len(triangles)} 0\n" + vs + "".join(
        f"3 {a} {b} {c}\n" for a, b, c in triangles)
    stl = ["solid s\n"]
    for tri in triangles:
        stl.append(" facet normal 0 0 0\n  outer loop\n")
        stl += [f"   vertex {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in positions[tri]]
        stl.append("  endloop\n endfacet\n")
    stl.append("endsolid s\n")
    return {".ply": ply.encode(), ".obj": obj.encode(), ".off": off.encode(), ".stl": "".join(stl).encode()}


HOSTILE_TOKENS = [b"nan", b"-nan", b"inf", b"-inf", b"1e308", b"-1", b"0", b"4294967299",
                  b"99999999999999999999", b"\x1b[2J", b"\x00", b"\xff\xfe", b"", b"-0"]


def mutate(data, rng):
    """One to four random edits: a byte flipped, a slice dropped or doubled, a number or
    hostile token put in place of a number, or the tail cut."""
    data = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        if not data:
            break
        kind = rng.randrange(5)
        i = rng.randrange(len(data))
        if kind == 0:
            data[i] ^= 1 << rng.randrange(8)
        elif kind == 1:
            del data[i:i + rng.randint(1, 64)]
        elif kind == 2:
            data[i:i] = data[i:i + rng.randint(1, 64)]
        elif kind == 3:
            j = i
            while j < len(data) and chr(data[j]) in "0123456789.-+e":
                j += 1
            data[i:j] = rng.choice(HOSTILE_TOKENS)
        else:
            del data[i:]
    return bytes(data)


HOSTILE_VALUES = [math.nan, math.inf, -math.inf, -1, -1e300, 0, 1e308, 2 ** 64, 2 ** 31,
                  "", "\x1b[31mred\x1b[0m", b"\x1b", "nan", [], {}, None, True, "<opaque>",
                  [math.nan, 1.0, 2.0], ("x",) * 3]
KEYWORDS = ["unit", "samples", "max_iterations", "azimuth_step", "elevations", "size",
            "supersample", "threshold_deg", "margin", "noise_k", "min_coverage", "fit_roi",
            "roi", "max_triangles", "iso", "backend", "metric", "zoom", "force"]
# register() takes only the surface, unit and fit keywords.
REGISTER_KEYWORDS = ["unit", "samples", "max_iterations", "fit_roi", "loss", "coarse", "fit_seed",
                     "allow_scale_mismatch", "symmetric"]
SMALL = dict(size=32, azimuth_step=90.0, elevations=[0.0], views=False, exr=False)


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    """The valid inputs (by kind) and the hostile paths, in a fresh folder."""
    folder = tmp_path_factory.mktemp("fuzz_inputs")
    positions, triangles = sphere_mesh()
    meshes = {}
    for ext, text in mesh_texts(positions, triangles).items():
        (folder / f"sphere{ext}").write_bytes(text)
        meshes[ext] = text
    corpus = pathlib.Path(__file__).resolve().parents[2] / "fuzz" / "corpus"
    others = {".mha": (corpus / "mha" / "blob_short.mha").read_bytes(),
              ".toml": (corpus / "scenario" / "condyle_dent.toml").read_bytes(),
              ".json": (corpus / "fit" / "fit.json").read_bytes()}
    fifo = folder / "fifo.ply"
    os.mkfifo(fifo)
    hostile_paths = [str(folder), str(fifo), "/dev/null", str(folder / "missing.ply"),
                     str(folder / "esc\x1b[2J.ply"), "", "/proc/self/mem"]
    return folder, meshes, others, (positions, triangles), hostile_paths


def build_cases(inputs):
    """(entry, args, kwargs) tuples, in a fixed order from SEED."""
    folder, meshes, others, (positions, triangles), hostile_paths = inputs
    rng = random.Random(SEED)
    reference = str(folder / "sphere.ply")
    cases = []

    def written(ext, data, n):
        path = folder / f"mutant_{n}{ext}"
        path.write_bytes(data)
        return str(path)

    for n in range(60):  # mutated files of every kind, loaded
        ext = rng.choice(list(meshes) + [".mha"])
        data = mutate(meshes.get(ext) or others[ext], rng)
        kwargs = {"iso": rng.choice([500.0, math.nan, -1e308])} if ext == ".mha" else {}
        cases.append(("load", [written(ext, data, n)], kwargs))
    for path in hostile_paths:
        cases += [("load", [path], {}), ("as_mesh", [path], {}),
                  ("analyse", [reference, reference], {"register": False, "output": path, **SMALL})]
    for n, v in enumerate(HOSTILE_VALUES):  # every hostile value as a path, a mesh, a keyword
        cases += [("load", [v], {}), ("as_mesh", [v], {}),
                  ("load", [reference], {rng.choice(["unit", "max_triangles", "iso"]): v}),
                  ("options", [], {KEYWORDS[n % len(KEYWORDS)]: v}),
                  ("transform", [reference, v], {})]
    for n in range(12):  # arrays: non-finite, huge, negative or out-of-range ids, wrong shapes
        p = positions.copy()
        t = triangles.copy()
        p[rng.randrange(len(p)), rng.randrange(3)] = rng.choice([math.nan, math.inf, 1e30, -1e38])
        t[rng.randrange(len(t)), rng.randrange(3)] = rng.choice([-1, len(p), 2 ** 31 - 1])
        cases += [("Mesh", [("array", p.tolist(), "f8"), ("array", triangles.tolist(), "i8")], {}),
                  ("Mesh", [("array", positions.tolist(), "f8"), ("array", t.tolist(), "i8")], {}),
                  ("as_mesh", [("pair", ("array", p.tolist(), "f4"), ("array", t.tolist(), "f8"))], {}),
                  ("Mesh", [("array", positions[:, :2].tolist(), "f8"), ("array", [], "i4")], {})]
    for n in range(12):  # whole runs on mutated meshes and fit/scenario files, hostile keywords
        ext = rng.choice(list(meshes))
        mutant = written(ext, mutate(meshes[ext], rng), 100 + n)
        fit = written(".json", mutate(others[".json"], rng), 100 + n)
        toml = written(".toml", mutate(others[".toml"], rng), 100 + n)
        key, v = rng.choice(REGISTER_KEYWORDS), rng.choice(HOSTILE_VALUES)
        cases += [("register", [reference, rng.choice([mutant, reference])], {key: v}),
                  ("analyse", [reference, mutant], {"register": False, **SMALL}),
                  ("analyse", [reference, reference], {"fit": rng.choice([fit, toml]), **SMALL}),
                  ("asymmetry", [mutant], {"plane": rng.choice(["x=0", "x=nan", "point=0,0,0;normal=0,0,0", v])})]
    return cases


class Worker:
    """A `python3 -c WORKER` process taking cases on stdin, answering each on stdout."""

    def __init__(self):
        self.process = subprocess.Popen([sys.executable, "-c", WORKER], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)

    def run(self, case):
        """("ok"|"raised", type, message), or ("signal"|"exit"|"hang", detail, "")."""
        self.process.stdin.write(base64.b64encode(pickle.dumps(case)) + b"\n")
        self.process.stdin.flush()
        ready, _, _ = select.select([self.process.stdout], [], [], CASE_TIMEOUT_S)
        if not ready:
            self.process.kill()
            self.process.wait()
            return ("hang", f"no answer in {CASE_TIMEOUT_S} s", "")
        line = self.process.stdout.readline()
        if not line:
            code = self.process.wait()
            return ("signal" if code < 0 else "exit", str(code), "")
        return pickle.loads(base64.b64decode(line))

    def alive(self):
        return self.process.poll() is None

    def close(self):
        if self.alive():
            self.process.stdin.close()
            self.process.wait()


def test_hostile_input_to_every_entry_point_raises_one_line_or_succeeds(inputs):
    pytest.importorskip("glint")
    cases = build_cases(inputs)
    failures = []
    worker = Worker()
    try:
        for n, case in enumerate(cases):
            if not worker.alive():
                worker = Worker()
            outcome, kind, message = worker.run(case)
            if outcome == "ok":
                continue
            if outcome != "raised":
                failures.append(f"case {n} {case[0]} {case[1]!r:.200} {case[2]!r:.120}: {outcome} {kind}")
            elif "\n" in message.strip() or not message.strip():
                failures.append(f"case {n} {case[0]}: {kind} message is not one line: {message!r:.300}")
    finally:
        worker.close()
    assert not failures, f"{len(failures)} of {len(cases)} cases failed:\n" + "\n".join(failures)


def test_a_message_quoting_bytes_that_are_not_utf8_keeps_them_escaped(tmp_path):
    """Found by the cases above: an error quoting a file's non-UTF-8 byte came out with an empty
    message (PyErr_SetString could not decode it)."""
    glint = pytest.importorskip("glint")
    path = tmp_path / "bad_index.ply"
    path.write_bytes(b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     b"property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                     b"end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\xb9\n")
    with pytest.raises(glint.InputError) as raised:
        glint.load(path)
    assert "9\\xb9" in str(raised.value) and "\n" not in str(raised.value)


def test_a_wrong_type_for_a_path_or_plane_is_refused_in_one_line(tmp_path):
    glint = pytest.importorskip("glint")
    with pytest.raises(TypeError, match=r"^load\(\): path must be a str or os.PathLike, not float$"):
        glint.load(1.5)
    with pytest.raises(TypeError, match=r"^asymmetry\(\): plane must be a str or None, not list$"):
        glint.asymmetry(tmp_path / "any.ply", plane=[1.0, 2.0])
    # The path and bool keywords of analyse, register, asymmetry and options: one line each
    # (pybind11's own refusal listed every signature over several lines).
    mesh = tmp_path / "any.ply"
    for call, keyword, value, expected in [
            (lambda **kw: glint.analyse(mesh, mesh, **kw), "output", 1.5,
             r"^analyse\(\): output must be a str, os.PathLike or None, not float$"),
            (lambda **kw: glint.analyse(mesh, mesh, **kw), "fit", 3,
             r"^analyse\(\): fit must be a str, os.PathLike or None, not int$"),
            (lambda **kw: glint.analyse(mesh, mesh, **kw), "register", "yes",
             r"^analyse\(\): register must be True or False, not str$"),
            (lambda **kw: glint.register(mesh, mesh, **kw), "output", [1],
             r"^register\(\): output must be a str, os.PathLike or None, not list$"),
            (lambda **kw: glint.asymmetry(mesh, **kw), "output", 1.5,
             r"^asymmetry\(\): output must be a str, os.PathLike or None, not float$"),
            (lambda **kw: glint.options(**kw), "register", 1,
             r"^options\(\): register must be True or False, not int$")]:
        with pytest.raises(TypeError, match=expected):
            call(**{keyword: value})
