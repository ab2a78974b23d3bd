#!/usr/bin/env python3
"""Property test of the output discipline (issue 52): for random layouts of inputs and outputs,
no input byte ever changes and glint never crashes.

Each case lays out, in a fresh folder (the run starts in its sub-folder d0), inputs of every kind a run reads: main mesh files, a ROI
mask, a volume whose header names its slices by a pattern, one whose header names them as a
LIST, a glTF whose buffer lies in a folder below it, and symbolic links to some of them. It then
runs one command (sweep with or without a mask, surface, volume-edit, info) with an output
chosen among the places a user could name: a new folder, a folder holding inputs, ".", "..",
a link, an input itself, a header's slice name; with --force or without. After each run every
input's bytes and the links must be as they were, and the exit code one of glint's (0-4, never
a signal). Seeds are fixed: a failure names the seed and the command, and reruns the same case.

  inputs_property_test.py GLINT WORKDIR [CASES]
"""
import hashlib
import os
import random
import shutil
import struct
import subprocess
import sys

GLINT, WORK = sys.argv[1], os.path.join(sys.argv[2], "inputs_property")
CASES = int(sys.argv[3]) if len(sys.argv) > 3 else 40
SMALL = ["--size", "32", "--azimuth-step", "90", "--elevations", "0", "--no-views", "--no-exr"]
CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
CUBE_F = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def write(path, data):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)


def cube_obj():
    return "".join(f"v {x} {y} {z}\n" for x, y, z in CUBE_V) + "".join(
        "f " + " ".join(str(i + 1) for i in face) + "\n" for face in CUBE_F)


def mask_ply():
    head = ("ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
            "property float z\nproperty int label\nelement face 0\nproperty list uchar int "
            "vertex_indices\nend_header\n")
    return head + "".join(f"{x} {y} {z} 1\n" for x, y, z in CUBE_V)


def slice_bytes(k):
    # 6 × 6 voxels of unsigned char: a bright square in the middle slices (a small blob).
    inside = 1 <= k <= 2
    return bytes(200 if inside and 1 <= i % 6 <= 4 and 1 <= i // 6 <= 4 else 0 for i in range(36))


def gltf():
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    idx = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    import json
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
           "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "buffers": [{"uri": "bins/data.bin", "byteLength": len(pos) + len(idx)}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": 6}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 1, 0]},
                         {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}
    return json.dumps(doc), pos + idx


def lay_out(root, rng):
    """Inputs under root in randomly named folders; returns (files, links, roles)."""
    dirs = [f"d{i}" for i in range(rng.randint(1, 3))]
    os.makedirs(os.path.join(root, "d0"), exist_ok=True)  # where the run starts
    pick = lambda: rng.choice(dirs)  # noqa: E731
    roles = {}
    roles["ref"] = f"{pick()}/ref.obj"
    roles["exa"] = f"{pick()}/exa.obj"
    roles["mask"] = f"{pick()}/m{rng.randint(0, 9)}.ply"
    slices = pick()
    roles["pattern"] = f"{pick()}/ct.mhd"
    roles["list"] = f"{pick()}/list.mhd"
    roles["gltf"] = f"{pick()}/scene.gltf"
    write(os.path.join(root, roles["ref"]), cube_obj())
    write(os.path.join(root, roles["exa"]), cube_obj())
    write(os.path.join(root, roles["mask"]), mask_ply())
    names = []
    for k in range(4):
        name = f"{slices}/s{k}.raw"
        write(os.path.join(root, name), slice_bytes(k))
        names.append(name)
    rel = os.path.relpath(os.path.join(root, slices), os.path.dirname(os.path.join(root, roles["pattern"])))
    write(os.path.join(root, roles["pattern"]),
          "ObjectType = Image\nNDims = 3\nDimSize = 6 6 4\nElementSpacing = 1 1 1\n"
          f"ElementType = MET_UCHAR\nElementDataFile = {rel}/s%d.raw 0 3 1\n")
    rel = os.path.relpath(os.path.join(root, slices), os.path.dirname(os.path.join(root, roles["list"])))
    write(os.path.join(root, roles["list"]),
          "ObjectType = Image\nNDims = 3\nDimSize = 6 6 4\nElementSpacing = 1 1 1\n"
          "ElementType = MET_UCHAR\nElementDataFile = LIST 2D\n" +
          "".join(f"{rel}/s{k}.raw\n" for k in range(4)))
    text, buffer = gltf()
    write(os.path.join(root, roles["gltf"]), text)
    buffer_name = os.path.join(os.path.dirname(roles["gltf"]), "bins", "data.bin")
    write(os.path.join(root, buffer_name), buffer)
    files = [roles[k] for k in ("ref", "exa", "mask", "pattern", "list", "gltf")] + names + [buffer_name]
    links = {}
    for k in rng.sample(["ref", "pattern", "gltf", "mask"], rng.randint(0, 2)):
        link = f"link_{k}{os.path.splitext(roles[k])[1]}"
        os.symlink(roles[k], os.path.join(root, link))
        links[link] = roles[k]
        roles[k] = link
    if rng.random() < 0.5:  # a link to a folder of inputs
        os.symlink(dirs[0], os.path.join(root, "linkdir"))
        links["linkdir"] = dirs[0]
    return files, links, roles, dirs, slices


def snapshot(root, files, links):
    state = {}
    for f in files:
        with open(os.path.join(root, f), "rb") as fh:
            state[f] = hashlib.sha256(fh.read()).hexdigest()
    for link, target in links.items():
        state[link] = "-> " + os.readlink(os.path.join(root, link))
    return state


def at(path):
    """A layout path as the run names it: runs start in d0, one folder below the layout's root."""
    return "../" + path


def output_choice(rng, files, dirs, slices, kind):
    if kind == "folder":
        # "." and ".." are the run's own folder (d0, holding inputs or not) and the layout's root.
        return rng.choice([".", "..", at("out"), at("new/out"), at("linkdir"), at(rng.choice(dirs)),
                           at(rng.choice(dirs) + "/out"), at(slices), at(f"{slices}/../{slices}"),
                           at(rng.choice(files))])
    if kind == "mhd":
        return at(rng.choice([f"{slices}/s1.mhd", f"{slices}/s3.mhd", "edited.mhd",
                              f"{rng.choice(dirs)}/ct.mhd", f"{rng.choice(dirs)}/x.mha"]))
    return at(rng.choice(["surface.ply", rng.choice(files), f"{slices}/s0.raw",
                          f"{rng.choice(dirs)}/s.ply"]))


def command(rng, roles, files, dirs, slices):
    what = rng.choice(["sweep", "sweep_mask", "surface", "volume_edit", "info", "sweep_gltf"])
    force = ["--force"] if rng.random() < 0.7 else []
    out = lambda kind: output_choice(rng, files, dirs, slices, kind)  # noqa: E731
    if what == "sweep":
        return ["sweep", at(roles["ref"]), at(roles["exa"]), *SMALL, "-o", out("folder"), *force]
    if what == "sweep_mask":
        flag = rng.choice(["--roi", "--fit-roi"])
        return ["sweep", at(roles["ref"]), at(roles["exa"]), *SMALL, flag,
                f"mask:{at(roles['mask'])}", "-o", out("folder"), *force]
    if what == "sweep_gltf":
        return ["sweep", at(roles["gltf"]), at(roles["gltf"]), *SMALL, "-o", out("folder"), *force]
    if what == "surface":
        return ["surface", at(rng.choice([roles["pattern"], roles["list"]])), "--iso", "100",
                "-o", out("file")]
    if what == "volume_edit":
        return ["volume-edit", at(rng.choice([roles["pattern"], roles["list"]])), "-o", out("mhd")]
    return ["info", at(rng.choice([roles["ref"], roles["gltf"], roles["pattern"], roles["list"]]))]


def main():
    failures = 0
    for seed in range(CASES):
        rng = random.Random(seed)
        root = os.path.join(WORK, f"case{seed}")
        shutil.rmtree(root, ignore_errors=True)
        os.makedirs(root)
        files, links, roles, dirs, slices = lay_out(root, rng)
        cwd = os.path.join(root, "d0")
        args = command(rng, roles, files, dirs, slices)
        before = snapshot(root, files, links)
        try:
            run = subprocess.run([GLINT, "--quiet", *args], cwd=cwd, capture_output=True, text=True,
                                 errors="replace", timeout=120)
            code = run.returncode
            err = run.stderr.strip()
        except subprocess.TimeoutExpired:
            code, err = "timeout", ""
        problems = []
        if code not in (0, 1, 2, 3, 4):
            problems.append(f"exit {code}")
        try:
            after = snapshot(root, files, links)
        except OSError as e:
            after = None
            problems.append(f"an input is gone: {e}")
        if after is not None and after != before:
            changed = [k for k in before if before[k] != after.get(k)]
            problems.append("inputs changed: " + ", ".join(changed))
        line = f"seed {seed}: (cd d0) glint {' '.join(args)} -> exit {code}"
        print(line + (f": {err.splitlines()[-1]}" if err else ""))
        if problems:
            failures += 1
            print(f"FAIL seed {seed}: " + "; ".join(problems))
    print(f"{CASES - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
