#!/usr/bin/env python3
"""Checks what real viewers read from a glint atlas against the values glint wrote.

The truth is atlas.ply as written, parsed here with nothing but the standard library:

  viewers_check.py vtk ATLAS_DIR
      VTK (python3-vtk9, the reader ParaView and 3D Slicer use) reads atlas.vtp and atlas.vtk:
      same points, triangles and every scalar (NaN exact in .vtp, the documented number in .vtk).
  viewers_check.py meshlab ATLAS_DIR MESHLAB_OUT.ply
      The PLY meshlabserver wrote after loading atlas.ply holds `quality` = the primary field.
  viewers_check.py cloudcompare ATLAS_DIR FIELD_PREFIX EXPORT.asc [EXPORT.asc …]
      CloudCompare's ASCII export of the atlas's vertices holds every scalar with its values.

Exit 0 when everything matches, 1 with the first mismatches listed.
"""
import math
import struct
import sys

PLY_TYPES = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I",
             "float": "f", "double": "d", "int8": "b", "uint8": "B", "int16": "h", "uint16": "H",
             "int32": "i", "uint32": "I", "float32": "f", "float64": "d"}
VTK_LEGACY_NAN = -9999.0  # mesh/write.h WriteOptions::vtk_legacy_nan


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


def scalar_names(ply):
    """The atlas scalars: every property except geometry, colour, label and the viewer copies."""
    fixed = {"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "alpha", "label", "quality"}
    return [n for n in ply if n not in fixed and not n.startswith("scalar_")]


def check_vtk(atlas):
    import vtk  # python3-vtk9
    ply = read_ply(f"{atlas}/atlas.ply")
    names = scalar_names(ply)
    problems = []
    for file, reader, nan_as in ((f"{atlas}/atlas.vtp", vtk.vtkXMLPolyDataReader(), None),
                                 (f"{atlas}/atlas.vtk", vtk.vtkPolyDataReader(), VTK_LEGACY_NAN)):
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
        for name in names:
            array = data.GetArray(name)
            if array is None:
                problems.append(f"{file}: no point-data array {name}")
                continue
            expected = [nan_as if (nan_as is not None and math.isnan(v)) else v for v in ply[name]]
            compare(f"{file} {name}", expected, [array.GetValue(i) for i in range(n)], problems)
        print(f"{file}: {n} points, {poly.GetNumberOfPolys()} triangles, {len(names)} scalars read by VTK "
              f"{vtk.vtkVersion.GetVTKVersion()}")
    return problems


def check_meshlab(atlas, out_ply):
    ply = read_ply(f"{atlas}/atlas.ply")
    written = read_ply(out_ply)
    problems = []
    if "quality" not in written:
        return [f"{out_ply}: MeshLab wrote no quality property (it read none)"]
    compare("MeshLab quality", ply["quality"], written["quality"], problems)
    # The quality glint wrote is the primary field (the metric's zoom-0 mean).
    primary = [n for n in scalar_names(ply) if n.endswith("_mean_z0")][0]
    compare(f"quality vs {primary}", ply[primary], ply["quality"], problems, tol=0)
    print(f"MeshLab kept quality on {len(written['quality'])} vertices (= {primary})")
    return problems


def read_asc(path):
    with open(path) as f:
        header = f.readline().lstrip("/").split()
        rows = [line.split() for line in f if line.strip()]
    return {name: [float(r[i]) for r in rows] for i, name in enumerate(header)}


def check_cloudcompare(atlas, prefix, exports):
    ply = read_ply(f"{atlas}/atlas.ply")
    names = scalar_names(ply)
    problems = []
    for path in exports:
        asc = read_asc(path)
        for axis in "XYZ":
            compare(f"{path} {axis}", ply[axis.lower()], asc.get(axis, []), problems, tol=1e-5)
        for name in names:
            # CloudCompare turns '_' into ' ' in names, and its ASCII export ' ' back into '_'.
            column = (prefix + name).replace(" ", "_")
            if column not in asc:
                problems.append(f"{path}: no scalar field {column} (CloudCompare fields: {sorted(asc)})")
                continue
            expected = ply[name]
            if path.endswith("vtk.asc"):
                expected = [VTK_LEGACY_NAN if math.isnan(v) else v for v in expected]
            compare(f"{path} {column}", expected, asc[column], problems, tol=1e-5)
        print(f"{path}: CloudCompare read {len(asc.get('X', []))} vertices with {len(names)} scalar fields")
    return problems


def main(argv):
    mode, atlas = argv[1], argv[2]
    if mode == "vtk":
        problems = check_vtk(atlas)
    elif mode == "meshlab":
        problems = check_meshlab(atlas, argv[3])
    elif mode == "cloudcompare":
        problems = check_cloudcompare(atlas, argv[3], argv[4:])
    else:
        raise SystemExit(f"unknown mode {mode}")
    for p in problems[:20]:
        print("MISMATCH:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
