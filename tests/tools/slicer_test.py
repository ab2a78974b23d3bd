"""glint as a 3D Slicer CLI module: `glint --xml` validates against the Execution Model schema
written down in tools/slicer/execution-model.xsd, and a call built from that XML the way
Slicer builds it (Slicer's vtkSlicerCLIModuleLogic: the executable, --returnparameterfile when
there are return parameters, then every flagged parameter in description order, then the index
parameters in index order; inputs written to and outputs read from a temporary folder with
each parameter's first file extension) runs and writes what the XML promises.

Run by CTest (cli.slicer_module) with GLINT_EXE and GLINT_XSD set."""
import copy
import os
import pathlib
import re
import subprocess

import pytest
from lxml import etree

GLINT = os.environ.get("GLINT_EXE", "")
XSD = os.environ.get("GLINT_XSD", "")
SIMPLE = {"integer", "float", "double", "integer-enumeration", "float-enumeration", "double-enumeration",
          "string-enumeration"}
FILES = {"image", "geometry", "table", "transform", "measurement"}
TEXT = {"string", "file", "directory", "integer-vector", "float-vector", "double-vector", "string-vector"}


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
    # What the module promises: two model inputs, an atlas model, a table and an image out.
    kinds = {(p.tag, p.get("type"), text(p, "channel")) for p in params if p.tag in FILES}
    assert ("geometry", "model", "input") in kinds and ("geometry", "model", "output") in kinds
    assert ("table", None, "output") in kinds and ("image", "vector", "output") in kinds


def slicer_command(root, inputs, outputs, params_file):
    """The argument list Slicer runs for this description: inputs/outputs map a parameter
    name to the file Slicer wrote / will read (unselected optional nodes are left out)."""
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


@pytest.fixture(scope="module")
def run(description, tmp_path_factory):
    folder = tmp_path_factory.mktemp("slicer")
    params = {text(p, "name"): p for p in parameters(description)}
    inputs = {n: temp_name(folder, p) for n, p in params.items() if p.tag in FILES and text(p, "channel") == "input"}
    outputs = {n: temp_name(folder, p) for n, p in params.items() if p.tag in FILES and text(p, "channel") == "output"}
    # What Slicer writes for two model nodes (its first extension: legacy VTK).
    subprocess.run([GLINT, "--quiet", "phantom", "condyle", "--scheme", "ico", "--resolution", "4", "-o",
                    str(inputs["reference"])], check=True)
    subprocess.run([GLINT, "--quiet", "phantom", "condyle", "--scheme", "uv", "--resolution", "48", "--damage",
                    "dent:center=2,-1,8.8 radius=3 depth=0.6", "--pose", "4,-3,5,0.3,-0.2,0.1", "-o",
                    str(inputs["examined"])], check=True)
    returned = folder / "1234_abcdefghij.params"
    command = slicer_command(description, inputs, outputs, returned)
    # note: Slicer's defaults sweep 60 views at 256 px; 64 px keeps the test to a few seconds.
    command[command.index("--size") + 1] = "64"
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
    # Nothing else is left beside them (the run's own folder was removed).
    expected = {p.name for p in [*inputs.values(), *outputs.values(), returned]}
    extra = {p.name for p in folder.iterdir()} - expected - {n.name + ".json" for n in inputs.values()}
    assert extra == set()


def test_missing_input_is_one_line_and_writes_nothing(description, tmp_path):
    params = {text(p, "name"): p for p in parameters(description)}
    outputs = {n: temp_name(tmp_path, p) for n, p in params.items() if p.tag in FILES and text(p, "channel") == "output"}
    inputs = {"reference": tmp_path / "gone.vtk", "examined": tmp_path / "gone_too.vtk"}
    done = subprocess.run(slicer_command(description, inputs, outputs, tmp_path / "r.params"), capture_output=True,
                          text=True)
    assert done.returncode == 2
    assert len(done.stderr.splitlines()) == 1 and "gone.vtk" in done.stderr
    assert list(tmp_path.iterdir()) == []


def test_bad_value_is_refused_naming_the_flag(description, tmp_path):
    command = slicer_command(description, {"reference": "a.vtk", "examined": "b.vtk"},
                             {"atlas": tmp_path / "atlas.vtp"}, tmp_path / "r.params")
    command[command.index("--size") + 1] = "big"
    done = subprocess.run(command, capture_output=True, text=True)
    assert done.returncode == 2 and "--size = \"big\": expected an integer in [8, 4096] (px)" in done.stderr
