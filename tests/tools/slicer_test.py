"""glint as a 3D Slicer CLI module: `glint --xml` validates against the Execution Model schema
written down in tools/slicer/execution-model.xsd, and a call built from that XML the way
Slicer builds it (Slicer's vtkSlicerCLIModuleLogic: the executable, --returnparameterfile when
there are return parameters, then every flagged parameter in description order, then the index
parameters in index order; inputs written to and outputs read from a temporary folder with
each parameter's first file extension; an ROI as "cx,cy,cz,rx,ry,rz", markups point lists as
files) runs and writes what the XML promises: for a model pair, and for a volume pair (NRRD
volumes written here as Slicer writes them: space, space directions, space origin, gzip).

Run by CTest (cli.slicer_module) with GLINT_EXE and GLINT_XSD set."""
import base64
import copy
import gzip
import json
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest
from lxml import etree

GLINT = os.environ.get("GLINT_EXE", "")
XSD = os.environ.get("GLINT_XSD", "")
SIMPLE = {"integer", "float", "double", "integer-enumeration", "float-enumeration", "double-enumeration",
          "string-enumeration"}
FILES = {"image", "geometry", "table", "transform", "measurement"}
MARKUPS = {"point", "region"}  # passed as text: "x,y,z" / "cx,cy,cz,rx,ry,rz"
FILES |= {"file", "pointfile"}
TEXT = {"string", "directory", "integer-vector", "float-vector", "double-vector", "string-vector"}


@pytest.fixture(scope="module")
def description():
    assert GLINT and XSD, "GLINT_EXE and GLINT_XSD must be set (ctest sets them)"
    out = subprocess.run([GLINT, "--xml"], check=True, capture_output=True).stdout
    return etree.fromstring(out)


@pytest.fixture(scope="module")
def schema():
    return etree.XMLSchema(etree.parse(XSD))


def parameters(root):
    """(group, element) of every parameter, in description order."""
    return [p for g in root.findall("parameters") for p in g if p.tag not in ("label", "description")]


def text(p, child):
    e = p.find(child)
    return "" if e is None or e.text is None else e.text.strip()


def is_return(p):
    return text(p, "channel") == "output" and not text(p, "flag") and not text(p, "longflag") and not text(p, "index")


def test_xml_validates_against_the_schema(description, schema):
    assert schema.validate(description), schema.error_log


def test_the_schema_rejects_a_broken_description(description, schema):
    broken = copy.deepcopy(description)
    parameters(broken)[0].remove(parameters(broken)[0].find("name"))
    assert not schema.validate(broken)
    wrong = copy.deepcopy(description)
    wrong.find(".//geometry/channel").text = "sideways"
    assert not schema.validate(wrong)
    number = copy.deepcopy(description)
    number.find(".//integer/default").text = "many"
    assert not schema.validate(number)


def test_rules_the_schema_cannot_state(description):
    params = parameters(description)
    names = [text(p, "name") for p in params]
    assert len(names) == len(set(names)), "names are unique"
    flags = [text(p, "longflag") for p in params if text(p, "longflag")]
    assert len(flags) == len(set(flags)), "long flags are unique"
    indices = sorted(int(text(p, "index")) for p in params if text(p, "index"))
    assert indices == list(range(len(indices))), "index parameters are numbered 0, 1, …"
    for p in params:
        assert text(p, "longflag") or text(p, "index") or is_return(p), f"{text(p, 'name')} cannot be passed"
        if is_return(p):
            assert p.tag in SIMPLE | {"boolean", "string"}, f"return parameter {text(p, 'name')} is not a value"
        if text(p, "longflag") in ("quiet", "json", "max-triangles", "version", "help"):
            pytest.fail(f"{text(p, 'name')} takes a flag of glint's own")
    # What the module promises: model and volume inputs, an atlas model, a table, images and the
    # report page out, ROIs and landmark lists as markups.
    kinds = {(p.tag, p.get("type"), text(p, "channel")) for p in params if p.tag in FILES}
    assert ("geometry", "model", "input") in kinds and ("geometry", "model", "output") in kinds
    assert ("image", "scalar", "input") in kinds and ("file", None, "output") in kinds
    assert ("table", None, "output") in kinds and ("image", "vector", "output") in kinds
    by_name = {text(p, "name"): p for p in params}
    assert by_name["report"].get("fileExtensions") == ".html"
    assert by_name["atlasPicture"].get("fileExtensions") == ".png"
    assert by_name["referenceVolume"].get("fileExtensions").startswith(".nrrd")
    for name in ("roi", "fitRoi", "referenceLandmarks", "examinedLandmarks", "seed"):
        # Left out, Slicer logs "Invalid coordinateSystemFlag value" and falls back to LPS: say it.
        assert by_name[name].get("coordinateSystem") == "lps", name
    assert by_name["roi"].tag == "region" and by_name["referenceLandmarks"].tag == "pointfile"


def slicer_command(root, inputs, outputs, params_file, markups=None):
    """The argument list Slicer runs for this description: inputs/outputs map a parameter
    name to the file Slicer wrote / will read, markups a point or region parameter to the text
    Slicer writes for its node (unselected optional nodes are left out)."""
    markups = markups or {}
    params = parameters(root)
    command = [GLINT]
    if any(is_return(p) for p in params):
        command += ["--returnparameterfile", str(params_file)]
    for p in params:
        flag = text(p, "longflag")
        if not flag:
            continue
        flag = "--" + flag.lstrip("-")
        name, value = text(p, "name"), text(p, "default")
        if p.tag == "boolean":
            command += [flag] if value == "true" else []
        elif p.tag in MARKUPS:
            command += [flag, markups[name]] if name in markups else []
        elif p.tag in SIMPLE:
            command += [flag, value]
        elif p.tag in TEXT:
            command += [flag, value] if value else []
        elif p.tag in FILES:
            chosen = inputs.get(name) or outputs.get(name)
            command += [flag, str(chosen)] if chosen else []
    for p in sorted((p for p in params if text(p, "index")), key=lambda p: int(text(p, "index"))):
        name = text(p, "name")
        command.append(str(inputs.get(name) or outputs[name]))
    return command


def temp_name(folder, p):
    """Slicer's temporary file for a node: a name with the parameter's first extension."""
    extension = (p.get("fileExtensions") or ".nrrd").split(",")[0]
    return folder / f"slicer_{text(p, 'name')}{extension}"


def node_files(description, folder, names):
    """Slicer's temporary file for each named parameter (inputs selected, outputs asked for)."""
    params = {text(p, "name"): p for p in parameters(description)}
    return {n: temp_name(folder, params[n]) for n in names}


def output_names(description):
    return [text(p, "name") for p in parameters(description) if p.tag in FILES and text(p, "channel") == "output"]


def small(command):
    """Slicer's defaults sweep 60 views at 256 px; 64 px keeps a test to a few seconds."""
    command[command.index("--size") + 1] = "64"
    return command


def condyle_pair(reference, examined, space=None, dent="2,-1,8.8"):
    """The condyle phantom and a posed copy with a dent (at (2, -1, 8.8)), as Slicer writes model
    nodes (legacy VTK); space: the SPACE= a Slicer model file states in its header, if any."""
    subprocess.run([GLINT, "--quiet", "phantom", "condyle", "--scheme", "ico", "--resolution", "4", "-o",
                    str(reference)], check=True)
    subprocess.run([GLINT, "--quiet", "phantom", "condyle", "--scheme", "uv", "--resolution", "48", "--damage",
                    f"dent:center={dent} radius=3 depth=0.6", "--pose", "4,-3,5,0.3,-0.2,0.1", "-o",
                    str(examined)], check=True)
    if space:
        for path in (reference, examined):
            lines = path.read_text().split("\n")
            lines[1] += f" SPACE={space}"  # Slicer writes its coordinate system in the VTK title line
            path.write_text("\n".join(lines))


@pytest.fixture(scope="module")
def run(description, tmp_path_factory):
    folder = tmp_path_factory.mktemp("slicer")
    inputs = node_files(description, folder, ["referenceModel", "examinedModel"])
    outputs = node_files(description, folder, output_names(description))
    condyle_pair(inputs["referenceModel"], inputs["examinedModel"])
    returned = folder / "1234_abcdefghij.params"
    command = small(slicer_command(description, inputs, outputs, returned))
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    return done, command, inputs, outputs, returned, folder


def test_slicer_call_runs(run):
    done, command, *_ = run
    assert done.returncode == 0, (command, done.stdout, done.stderr)
    assert command[1] == "--returnparameterfile" and command[3].startswith("--")


def test_progress_is_reported_as_slicer_reads_it(run):
    stdout = run[0].stdout
    values = [float(v) for v in re.findall(r"<filter-progress>([^<]*)</filter-progress>", stdout)]
    assert len(values) > 5 and values == sorted(values) and values[-1] == 1.0 and 0 <= values[0] < 0.5
    assert "<filter-start>" in stdout and "<filter-end>" in stdout


def return_values(path):
    values = {}
    for line in path.read_text().splitlines():
        key, sep, value = line.partition(" = ")
        assert sep and key not in values, f"bad line {line!r}"
        values[key] = value
    return values


def test_return_parameters_are_written(run, description):
    _, _, _, _, returned, _ = run
    values = return_values(returned)
    promised = {text(p, "name") for p in parameters(description) if is_return(p)}
    assert set(values) == promised
    assert int(values["regionCount"]) == 1
    assert float(values["peakDepth"]) < -0.3 and float(values["volumeLost"]) > 0
    assert float(values["volumeGained"]) == 0 and float(values["coverage"]) > 90
    # The pose rotated the examined copy by about 7.1° (rx 4, ry -3, rz 5).
    assert 6.5 < float(values["fitRotationDeg"]) < 7.7 and float(values["fitRms"]) > 0
    assert values["lengthUnit"] == "mm"


def test_outputs_are_where_slicer_reads_them(run):
    _, _, inputs, outputs, returned, folder = run
    vtp = etree.parse(str(outputs["atlas"])).getroot()
    assert vtp.get("type") == "PolyData"
    arrays = {a.get("Name") for a in vtp.iter("DataArray")}
    assert {"angle_mean_deg_z0", "shape_change_mm", "region_id_z0", "seen_z0"} <= arrays
    # Slicer opens the model on its active scalar: the signed shape change, with its unit.
    assert vtp.find(".//PointData").get("Scalars") == "shape_change_mm"
    points = int(vtp.find(".//Piece").get("NumberOfPoints"))
    assert points == 2562  # the ico-4 condyle's vertices: the atlas is the reference
    rows = outputs["regions"].read_text().splitlines()
    assert "area" in rows[0] and len(rows) == 1 + int(return_values(returned)["regionCount"])
    assert outputs["mosaic"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert outputs["atlasPicture"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    regions = report_regions(outputs["report"])
    assert [r["kind"] for r in regions] == ["dent"]
    assert np.linalg.norm(np.array(regions[0]["centroid"]) - [2, -1, 8.8]) < 1.0
    # Nothing else is left beside them (the run's own folder was removed).
    expected = {p.name for p in [*inputs.values(), *outputs.values(), returned]}
    extra = {p.name for p in folder.iterdir()} - expected - {n.name + ".json" for n in inputs.values()}
    assert extra == set()


def vtp_array(path, name):
    """A Float32 array of glint's VTK XML atlas (binary: base64 of a UInt32 byte count + data)."""
    array = next(a for a in etree.parse(str(path)).getroot().iter("DataArray") if a.get("Name") == name)
    raw = base64.b64decode(array.text.strip())
    return np.frombuffer(raw[4:4 + int(np.frombuffer(raw[:4], "<u4")[0])], "<f4")


def report_data(page):
    """report.json as report.html carries it (the page's own data, as its script reads them)."""
    html = page.read_text()
    assert html.startswith("<!DOCTYPE html>") or "<html" in html[:500]
    data = re.search(r'<script id="glint-data" type="application/json">(.*?)</script>', html, re.S)
    return json.loads(data.group(1))["report"]


def report_regions(page):
    """The regions of zoom 0 in report.html."""
    return report_data(page)["zooms"][0]["regions"]


def test_missing_input_is_one_line_and_writes_nothing(description, tmp_path):
    params = {text(p, "name"): p for p in parameters(description)}
    outputs = {n: temp_name(tmp_path, p) for n, p in params.items() if p.tag in FILES and text(p, "channel") == "output"}
    inputs = {"referenceModel": tmp_path / "gone.vtk", "examinedModel": tmp_path / "gone_too.vtk"}
    done = subprocess.run(slicer_command(description, inputs, outputs, tmp_path / "r.params"), capture_output=True,
                          text=True)
    assert done.returncode == 2
    assert len(done.stderr.splitlines()) == 1 and "gone.vtk" in done.stderr
    assert list(tmp_path.iterdir()) == []


def test_bad_value_is_refused_naming_the_flag(description, tmp_path):
    command = slicer_command(description, {"referenceModel": "a.vtk", "examinedModel": "b.vtk"},
                             {"atlas": tmp_path / "atlas.vtp"}, tmp_path / "r.params")
    command[command.index("--size") + 1] = "big"
    done = subprocess.run(command, capture_output=True, text=True)
    assert done.returncode == 2 and "--size = \"big\": expected an integer in [8, 4096] (px)" in done.stderr


# --- ROI markups: Slicer's sign convention ------------------------------------------------------
def run_call(description, folder, inputs, markups=None, outputs=None):
    outputs = outputs or node_files(description, folder, ["atlas", "report", "regions"])
    returned = folder / "r.params"
    command = small(slicer_command(description, inputs, outputs, returned, markups))
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, (command, done.stdout, done.stderr)
    return return_values(returned), outputs


@pytest.fixture(scope="module")
def ras_pair(description, tmp_path_factory):
    """The condyle pair in files that state SPACE=RAS: the module turns them into LPS, Slicer's
    space, so the dent at RAS (6, -1, 7.9) is at LPS (-6, 1, 7.9), 12 mm from its mirror image."""
    folder = tmp_path_factory.mktemp("ras")
    inputs = node_files(description, folder, ["referenceModel", "examinedModel"])
    condyle_pair(inputs["referenceModel"], inputs["examinedModel"], space="RAS", dent="6,-1,7.9")
    return inputs


def test_roi_around_the_dent_in_lps_finds_it(description, ras_pair, tmp_path):
    values, outputs = run_call(description, tmp_path, ras_pair, {"roi": "-6,1,7.9,4,4,4"})
    assert int(values["regionCount"]) == 1 and float(values["peakDepth"]) < -0.3
    centroid = np.array(report_regions(outputs["report"])[0]["centroid"])
    assert np.linalg.norm(centroid - [-6, 1, 7.9]) < 1.0, centroid
    # The atlas is in LPS (what Slicer assumes of a model file that states no space), and only
    # the box was swept: every vertex seen lies in it (give or take a triangle, 1 mm).
    points, seen = vtp_array(outputs["atlas"], "Points").reshape(-1, 3), vtp_array(outputs["atlas"], "seen_z0")
    inside = np.all(np.abs(points - [-6, 1, 7.9]) <= 4 + 1.0, axis=1)
    assert seen.max() == 1 and np.all(inside[seen > 0]), points[(seen > 0) & ~inside][:5]
    assert inside.mean() < 0.2  # and most of the surface lies outside it


def test_roi_restricts_the_analysis(description, ras_pair, tmp_path):
    # The same box at the dent's RAS numbers (RAS read as if it were LPS) holds no damage.
    values, _ = run_call(description, tmp_path, ras_pair, {"roi": "6,-1,7.9,4,4,4"})
    assert int(values["regionCount"]) == 0, values


# --- volumes, as Slicer writes them --------------------------------------------------------------
CENTRE = np.array([10.0, -20.0, 30.0])  # LPS, mm
RADII = np.array([8.0, 6.0, 5.0])
DENT = CENTRE + [8.0, 0.0, 0.0]  # on the surface, +x (left); 1.3 mm deep
PEBBLE = CENTRE + [-8.5, 7.0, 3.0]  # a loose 1.5 mm ball beside the ellipsoid (right, posterior)


def field(points, dent):
    """Grey values of an ellipsoid (1000 inside, 0 outside) with an optional spherical bite and a
    loose pebble, as a smooth function of an approximate signed distance so the iso-surface at
    500 is exact."""
    d = (np.linalg.norm((points - CENTRE) / RADII, axis=-1) - 1.0) * 5.0
    d = np.minimum(d, np.linalg.norm(points - PEBBLE, axis=-1) - 1.5)
    if dent:
        bite = CENTRE + [8.0 + 1.2, 0.0, 0.0]
        d = np.maximum(d, 2.5 - np.linalg.norm(points - bite, axis=-1))
    return np.round(1000.0 / (1.0 + np.exp(d / 0.3))).astype("<i2")


def write_nrrd(path, dent, space="left-posterior-superior", tilt_deg=0.0):
    """A volume as Slicer's NRRD writer stores it: short voxels, gzip, space directions with
    flipped axes (tilted about z by tilt_deg: an oblique scan) and a non-zero origin. `space`
    RAS stores the same object in RAS numbers."""
    c, s = np.cos(np.radians(tilt_deg)), np.sin(np.radians(tilt_deg))
    tilt = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    directions = tilt @ np.diag([-0.5, -0.5, 0.6])  # columns: the physical step of i, j, k (LPS)
    size = (52, 44, 26)
    origin = CENTRE + tilt @ [13.0, 11.0, -7.5]
    index = np.stack(np.meshgrid(*[np.arange(n) for n in size], indexing="ij"), axis=-1)
    voxels = field(origin + index @ directions.T, dent)
    if space == "right-anterior-superior":
        flip = np.diag([-1.0, -1.0, 1.0])
        directions, origin = flip @ directions, flip @ origin
    vector = lambda v: "(" + ",".join(f"{x:.10g}" for x in v) + ")"
    header = ("NRRD0004\n# Complete NRRD file format specification at:\n"
              "# http://teem.sourceforge.net/nrrd/format.html\ntype: short\ndimension: 3\n"
              f"space: {space}\nsizes: {size[0]} {size[1]} {size[2]}\n"
              f"space directions: {' '.join(vector(directions[:, a]) for a in range(3))}\n"
              "kinds: domain domain domain\nendian: little\nencoding: gzip\n"
              f"space origin: {vector(origin)}\n\n")
    path.write_bytes(header.encode() + gzip.compress(voxels.tobytes(order="F")))


@pytest.fixture(scope="module")
def volume_pair(description, tmp_path_factory):
    folder = tmp_path_factory.mktemp("volumes")
    inputs = node_files(description, folder, ["referenceVolume", "examinedVolume"])
    write_nrrd(inputs["referenceVolume"], dent=False)
    # The examined one on an oblique grid, in RAS numbers: the reader must turn it into the same
    # LPS object.
    write_nrrd(inputs["examinedVolume"], dent=True, space="right-anterior-superior", tilt_deg=8.0)
    return inputs


def test_volume_pair_finds_the_dent(description, volume_pair, tmp_path):
    assert volume_pair["referenceVolume"].suffix == ".nrrd"  # Slicer writes a volume node with its first extension
    values, outputs = run_call(description, tmp_path, volume_pair,
                               outputs=node_files(description, tmp_path, output_names(description)))
    assert int(values["regionCount"]) == 1 and -1.6 < float(values["peakDepth"]) < -0.9
    assert float(values["fitRotationDeg"]) < 1.0  # the same object: nothing to move
    centroid = np.array(report_regions(outputs["report"])[0]["centroid"])
    assert np.linalg.norm(centroid - DENT) < 1.0, centroid
    assert outputs["atlasPicture"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = outputs["regions"].read_text().splitlines()
    assert len(rows) == 2 and ",dent," in rows[1]


def test_volume_pair_from_nifti(description, volume_pair, tmp_path):
    # A volume node written as NIfTI (Slicer's .nii goes through ITK, as glint volume-edit's does:
    # RAS in the file's sform, LPS in memory) lands where its NRRD twin does.
    nifti = tmp_path / "slicer_referenceVolume.nii"
    subprocess.run([GLINT, "--quiet", "volume-edit", str(volume_pair["referenceVolume"]), "-o", str(nifti)],
                   check=True)
    values, outputs = run_call(description, tmp_path, {**volume_pair, "referenceVolume": nifti})
    assert int(values["regionCount"]) == 1 and float(values["fitRotationDeg"]) < 1.0
    centroid = np.array(report_regions(outputs["report"])[0]["centroid"])
    assert np.linalg.norm(centroid - DENT) < 1.0, centroid


def test_volume_iso_is_passed(description, volume_pair, tmp_path):
    # iso 900 lies inside the smooth edge: a slightly smaller surface, the same dent.
    command = slicer_command(description, volume_pair, node_files(description, tmp_path, ["atlas"]),
                             tmp_path / "r.params")
    command[command.index("--iso") + 1] = "900"
    done = subprocess.run(small(command), capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert int(return_values(tmp_path / "r.params")["regionCount"]) == 1


def test_volume_seed_point_keeps_the_part_nearest_it(description, volume_pair, tmp_path):
    # A point just above the pebble, as Slicer passes it for coordinateSystem="lps" (the
    # volume's own frame), keeps the pebble alone and drops the ellipsoid with its dent.
    seed = ",".join(f"{x:g}" for x in PEBBLE + [0.0, 0.0, 1.4])
    values, outputs = run_call(description, tmp_path, volume_pair, {"seed": seed})
    points = vtp_array(outputs["atlas"], "Points").reshape(-1, 3)
    # (the pebble's surface, 1.5 mm give or take a voxel; the ellipsoid is more than 3 mm away)
    assert len(points) > 20 and np.linalg.norm(points - PEBBLE, axis=1).max() < 2.3
    assert int(values["regionCount"]) == 0


# --- landmarks as markups point lists ------------------------------------------------------------
def write_mrk_json(path, points_lps, coordinate_system):
    flip = np.array([-1.0, -1.0, 1.0]) if coordinate_system == "RAS" else np.ones(3)
    path.write_text(json.dumps({
        "@schema": "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/"
                   "Schema/markups-schema-v1.0.3.json#",
        "markups": [{"type": "Fiducial", "coordinateSystem": coordinate_system, "coordinateUnits": "mm",
                     "controlPoints": [{"id": str(i + 1), "label": f"F-{i + 1}", "position": list(p * flip),
                                        "positionStatus": "defined"} for i, p in enumerate(points_lps)]}]}))


def write_fcsv(path, points_lps):
    lines = ["# Markups fiducial file version = 5.6", "# CoordinateSystem = LPS",
             "# columns = id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID"]
    lines += [f"{i + 1},{p[0]},{p[1]},{p[2]},0,0,0,1,1,1,0,F-{i + 1},," for i, p in enumerate(points_lps)]
    path.write_text("\n".join(lines) + "\n")


LANDMARKS = [CENTRE + v for v in ([0, 6, 0], [0, 0, 5], [-8, 0, 0], [0, -6, 0])]


def test_landmarks_from_markups_files_start_the_fit(description, volume_pair, tmp_path):
    # The reference list in RAS numbers (.mrk.json), the examined one in LPS (.fcsv): read right,
    # they are the same points and the fit starts (and stays) at the identity; read wrong, it
    # starts half a turn about z away, and the ellipsoid fits there as well.
    inputs = dict(volume_pair)
    inputs["referenceLandmarks"] = tmp_path / "slicer_referenceLandmarks.mrk.json"
    inputs["examinedLandmarks"] = tmp_path / "slicer_examinedLandmarks.fcsv"
    write_mrk_json(inputs["referenceLandmarks"], LANDMARKS, "RAS")
    write_fcsv(inputs["examinedLandmarks"], LANDMARKS)
    values, outputs = run_call(description, tmp_path, inputs)
    assert float(values["fitRotationDeg"]) < 1.0 and int(values["regionCount"]) == 1
    recorded = report_data(outputs["report"])["inputs"]  # provenance names both point files
    assert sorted(pathlib.Path(i["path"]).name for i in recorded if i["role"] == "landmarks") == \
        sorted(inputs[n].name for n in ("examinedLandmarks", "referenceLandmarks"))
    centroid = np.array(report_regions(outputs["report"])[0]["centroid"])
    assert np.linalg.norm(centroid - DENT) < 1.0, centroid


# --- bad input: one line, exit 2, no output -------------------------------------------------------
def bad_calls(tmp_path, model_pair, volume_pair):
    broken_json = tmp_path / "broken.mrk.json"
    broken_json.write_text('{"markups": [{"controlPoints": [{"position": [1, 2')
    bad_line = tmp_path / "bad.fcsv"
    write_fcsv(bad_line, LANDMARKS)
    bad_line.write_text(bad_line.read_text().replace(f"3,{LANDMARKS[2][0]}", "3,left"))
    few = tmp_path / "few.fcsv"
    write_fcsv(few, LANDMARKS[:3])
    good = tmp_path / "good.fcsv"
    write_fcsv(good, LANDMARKS)
    return {
        "zero radius": ({**model_pair}, {"roi": "1,2,3,0,4,4"}, {}, "radius must be positive"),
        "rotated roi": ({**model_pair}, {"fitRoi": "1,2,3,4,4,4,1,0,0,0,0.6,0.8,0,-0.8,0.6"}, {}, "rotated"),
        "malformed markups json": ({**volume_pair, "referenceLandmarks": broken_json, "examinedLandmarks": good},
                                   {}, {}, "broken.mrk.json"),
        "malformed markups line": ({**volume_pair, "referenceLandmarks": bad_line, "examinedLandmarks": good},
                                   {}, {}, "bad.fcsv\" line 6: x,y,z: 'left' is not a number"),
        "unpaired landmarks": ({**volume_pair, "referenceLandmarks": few, "examinedLandmarks": good},
                               {}, {}, "3 reference landmarks and 4 examined landmarks"),
        "no surface at the iso value": ({**volume_pair}, {}, {"--iso": "5000"}, "5000"),
        "largest and seed": ({**volume_pair}, {"seed": "10,-20,35"}, {"--iso": "500", "+": "--largest"},
                             "--largest and --seed both given"),
        "model and volume": ({**volume_pair, "referenceModel": model_pair["referenceModel"]}, {}, {},
                             "both --referenceModel and --referenceVolume"),
    }


@pytest.mark.parametrize("case", ["zero radius", "rotated roi", "malformed markups json", "malformed markups line",
                                  "unpaired landmarks", "no surface at the iso value", "largest and seed",
                                  "model and volume"])
def test_bad_input_is_one_line(description, ras_pair, volume_pair, tmp_path, case):
    inputs, markups, replace, expected = bad_calls(tmp_path, ras_pair, volume_pair)[case]
    outputs = node_files(description, tmp_path / "out", output_names(description))
    (tmp_path / "out").mkdir()
    command = slicer_command(description, inputs, outputs, tmp_path / "r.params", markups)
    for flag, value in replace.items():
        if flag == "+":  # a boolean the user ticked
            command.insert(1, value)
        else:
            command[command.index(flag) + 1] = value
    done = subprocess.run(small(command), capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, (done.stdout, done.stderr)
    assert len(done.stderr.splitlines()) == 1 and expected in done.stderr, done.stderr
    assert list((tmp_path / "out").iterdir()) == []
