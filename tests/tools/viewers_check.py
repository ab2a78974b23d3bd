#!/usr/bin/env python3
"""Checks what real viewers read from a glint atlas against the values glint wrote.

The truth is atlas.ply as written, parsed here with nothing but the standard library. Every
mode first checks the atlas itself (docs/outputs.md, "The atlas fields"): its first field is the signed
shape change named with its unit (shape_change_mm), written once as scalar_<name> (no other
copy but MeshLab's `quality`, which holds the same values), no field holds NaN, and some
vertices are unseen (seen_z0 = 0, their angles 0), so the viewers meet the sentinel.

  viewers_check.py vtk ATLAS_DIR
      VTK (python3-vtk9, the reader ParaView and 3D Slicer use) reads atlas.vtp and atlas.vtk:
      same points, triangles and every field, and the shape change as the active scalars.
  viewers_check.py meshlab ATLAS_DIR MESHLAB_OUT.ply [COLORIZED.ply]
      The PLY meshlabserver wrote after loading atlas.ply holds `quality` = the shape change;
      after "Colorize by vertex Quality", its colours follow the quality (not one colour).
  viewers_check.py cloudcompare ATLAS_DIR FIELD_PREFIX EXPORT.asc [EXPORT.asc …]
      CloudCompare's ASCII export of the atlas's vertices holds every field with its values.

Exit 0 when everything matches, 1 with the first mismatches listed.
"""
import math
import struct
import sys

PLY_TYPES = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I",
             "float": "f", "double": "d", "int8": "b", "uint8": "B", "int16": "h", "uint16": "H",
             "int32": "i", "uint32": "I", "float32": "f", "float64": "d"}


def read_ply(path):
    """Vertex properties of a binary little-endian PLY: {name: [values]} in file order."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in header:
        raise SystemExit(f"{path}: not binary little endian")
    props, count, in_vertex = [], 0, False
    for line in header:
        w = line.split()
        if w[:2] == ["element", "vertex"]:
            count, in_vertex = int(w[2]), True
        elif w and w[0] == "element":
            in_vertex = False
        elif in_vertex and w[0] == "property" and w[1] != "list":
            props.append((w[2], PLY_TYPES[w[1]]))
    fmt = "<" + "".join(t for _, t in props)
    size = struct.calcsize(fmt)
    out = {name: [] for name, _ in props}
    for v in range(count):
        values = struct.unpack_from(fmt, data, end + v * size)
        for (name, _), x in zip(props, values):
            out[name].append(x)
    return out


def same(a, b, tol):
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    return abs(a - b) <= tol * max(1.0, abs(a))


def compare(what, expected, found, problems, tol=1e-6):
    if len(expected) != len(found):
        problems.append(f"{what}: {len(found)} values, expected {len(expected)}")
        return
    bad = [i for i, (e, f) in enumerate(zip(expected, found)) if not same(e, f, tol)]
    if bad:
        i = bad[0]
        problems.append(f"{what}: {len(bad)} of {len(expected)} values differ, first vertex {i}: "
                        f"{found[i]} read, {expected[i]} written")


def atlas_fields(ply):
    """The atlas fields in file order: the PLY's scalar_<name> properties, as <name>."""
    return {n[len("scalar_"):]: v for n, v in ply.items() if n.startswith("scalar_")}


def check_atlas(atlas):
    """The atlas.ply itself: what every viewer then reads. Returns (fields, problems)."""
    ply = read_ply(f"{atlas}/atlas.ply")
    fields = atlas_fields(ply)
    problems = []
    names = list(fields)
    if not names or not names[0].startswith("shape_change_"):
        problems.append(f"atlas.ply: the first field is {names[:1]}, not shape_change_<unit>")
    fixed = {"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "quality"}
    copies = [n for n in ply if n not in fixed and not n.startswith("scalar_")]
    if copies:
        problems.append(f"atlas.ply: properties other than scalar_<name>: {copies}")
    for name, values in list(fields.items()) + [("quality", ply.get("quality", []))]:
        bad = sum(1 for v in values if not math.isfinite(v))
        if bad:
            problems.append(f"atlas.ply: {name} holds {bad} NaN or infinite values")
    if names and ply.get("quality") != fields[names[0]]:
        problems.append(f"atlas.ply: quality is not {names[0]}")
    unseen = [i for i, s in enumerate(fields.get("seen_z0", [])) if s == 0]
    if not unseen:
        problems.append("atlas.ply: no unseen vertex (seen_z0 = 0): the fixture proves nothing")
    angles = [n for n in names if n.endswith("_z0") and ("_mean_" in n or "_max_" in n)]
    for name in angles:
        if any(fields[name][i] != 0 for i in unseen):
            problems.append(f"atlas.ply: {name} is not 0 at every unseen vertex")
    print(f"atlas.ply: fields {names}; {len(unseen)} of {len(ply['x'])} vertices unseen at zoom 0")
    return ply, fields, problems


def check_vtk(atlas):
    import vtk  # python3-vtk9
    ply, fields, problems = check_atlas(atlas)
    shape = next(iter(fields), "")
    for file, reader in ((f"{atlas}/atlas.vtp", vtk.vtkXMLPolyDataReader()),
                         (f"{atlas}/atlas.vtk", vtk.vtkPolyDataReader())):
        reader.SetFileName(file)
        if hasattr(reader, "ReadAllScalarsOn"):
            reader.ReadAllScalarsOn()
            reader.ReadAllColorScalarsOn()
        reader.Update()
        poly = reader.GetOutput()
        n = poly.GetNumberOfPoints()
        if n != len(ply["x"]) or poly.GetNumberOfPolys() == 0:
            problems.append(f"{file}: {n} points / {poly.GetNumberOfPolys()} polygons read")
            continue
        for k, axis in enumerate("xyz"):
            compare(f"{file} {axis}", ply[axis], [poly.GetPoint(i)[k] for i in range(n)], problems)
        data = poly.GetPointData()
        # What ParaView and Slicer colour by when the file opens.
        active = data.GetScalars().GetName() if data.GetScalars() is not None else None
        if active != shape:
            problems.append(f"{file}: the active scalars are {active}, not {shape}")
        for name, values in fields.items():
            array = data.GetArray(name)
            if array is None:
                problems.append(f"{file}: no point-data array {name}")
                continue
            compare(f"{file} {name}", values, [array.GetValue(i) for i in range(n)], problems)
        print(f"{file}: {n} points, {poly.GetNumberOfPolys()} triangles, {len(fields)} fields read by VTK "
              f"{vtk.vtkVersion.GetVTKVersion()}, active scalars {active}")
    return problems


def check_meshlab(atlas, out_ply, colorized=None):
    _, fields, problems = check_atlas(atlas)
    shape = next(iter(fields), "")
    if not shape:
        return problems
    written = read_ply(out_ply)
    if "quality" not in written:
        return problems + [f"{out_ply}: MeshLab wrote no quality property (it read none)"]
    compare(f"MeshLab quality vs {shape}", fields[shape], written["quality"], problems)
    print(f"MeshLab kept quality on {len(written['quality'])} vertices (= {shape})")
    if colorized:
        c = read_ply(colorized)
        colours = set(zip(c.get("red", []), c.get("green", []), c.get("blue", [])))
        compare(f"{colorized} quality vs {shape}", fields[shape], c.get("quality", []), problems)
        if len(colours) < 16:
            problems.append(f"{colorized}: Colorize by vertex Quality gave {len(colours)} colours")
        print(f"MeshLab's Colorize by vertex Quality: {len(colours)} colours on {len(c['x'])} vertices")
    return problems


def read_asc(path):
    with open(path) as f:
        header = f.readline().lstrip("/").split()
        rows = [line.split() for line in f if line.strip()]
    return {name: [float(r[i]) for r in rows] for i, name in enumerate(header)}


def check_cloudcompare(atlas, prefix, exports):
    ply, fields, problems = check_atlas(atlas)
    for path in exports:
        asc = read_asc(path)
        for axis in "XYZ":
            compare(f"{path} {axis}", ply[axis.lower()], asc.get(axis, []), problems, tol=1e-5)
        for name, values in fields.items():
            # CloudCompare shows scalar_<name> as <name>, turns '_' into ' ' in names, and its
            # ASCII export ' ' back into '_'.
            column = (prefix + name).replace(" ", "_")
            if column not in asc:
                problems.append(f"{path}: no scalar field {column} (CloudCompare fields: {sorted(asc)})")
                continue
            compare(f"{path} {column}", values, asc[column], problems, tol=1e-5)
        print(f"{path}: CloudCompare read {len(asc.get('X', []))} vertices with {len(fields)} scalar fields")
    return problems


def main(argv):
    mode, atlas = argv[1], argv[2]
    if mode == "vtk":
        problems = check_vtk(atlas)
    elif mode == "meshlab":
        problems = check_meshlab(atlas, argv[3], argv[4] if len(argv) > 4 else None)
    elif mode == "cloudcompare":
        problems = check_cloudcompare(atlas, argv[3], argv[4:])
    else:
        raise SystemExit(f"unknown mode {mode}")
    for p in problems[:20]:
        print("MISMATCH:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
