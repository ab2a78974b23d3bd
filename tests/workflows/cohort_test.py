"""The Snakemake cohort workflow (workflows/cohort) on a small generated cohort: three subjects
of condyle phantoms at two or three time points with known damage between consecutive scans.
The cohort table's numbers are checked against each pair's report.json and against the damage
that was made. Run by CTest (workflow.cohort) with GLINT_EXE and GLINT_SOURCE_DIR set."""
import csv
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

import pytest

SOURCE = pathlib.Path(os.environ.get("GLINT_SOURCE_DIR", "."))
GLINT = os.environ.get("GLINT_EXE", "")
WORKFLOW = SOURCE / "workflows" / "cohort"
sys.path.insert(0, str(WORKFLOW))
import cohort  # noqa: E402
import summary  # noqa: E402
import summary_html  # noqa: E402

DENT = "dent:center=2,-1,8.8 radius=3 depth=0.6"    # on the condyle's top
BUMP = "bump:center=-5,0,7 radius=2.5 depth=0.5"    # on its side, 7 mm from the dent
# Small sweeps keep each pair near a second on two cores.
SMALL = ["size=64", "azimuth_step=60", "elevations=[-45,0,45]"]


def phantom(path, *args):
    subprocess.run([GLINT, "--quiet", "phantom", "condyle", *args, "-o", str(path)], check=True)


@pytest.fixture(scope="module")
def cohort_run(tmp_path_factory):
    assert GLINT, "GLINT_EXE must be set (ctest sets it)"
    data = tmp_path_factory.mktemp("scans")
    # Subject A: clean, then a dent, then the same dent and a new bump (re-tessellated, moved).
    phantom(data / "a0.ply", "--scheme", "ico", "--resolution", "4")
    phantom(data / "a1.ply", "--scheme", "uv", "--resolution", "48", "--damage", DENT, "--pose", "4,-3,5,0.3,-0.2,0.1")
    phantom(data / "a2.ply", "--scheme", "ico", "--resolution", "5", "--damage", DENT, "--damage", BUMP,
            "--pose", "-3,2,-4,-0.2,0.1,0.3")
    # Subject B: two scans of an unchanged surface (time points as text: T0 < T1).
    phantom(data / "b0.ply", "--scheme", "ico", "--resolution", "4")
    phantom(data / "b1.ply", "--scheme", "uv", "--resolution", "40", "--pose", "2,3,-2,0.1,0.2,-0.1")
    # Subject C: a dent and a bump appear, but the ROI analyses only the dent's neighbourhood.
    phantom(data / "c0.ply", "--scheme", "ico", "--resolution", "4")
    phantom(data / "c1.ply", "--scheme", "uv", "--resolution", "48", "--damage", DENT, "--damage", BUMP,
            "--pose", "-2,4,3,0.2,0.3,0.1")
    manifest = data / "manifest.csv"
    manifest.write_text("subject,timepoint,path,iso,roi,landmarks\n"
                        "A,1,a1.ply,,,\nA,0,a0.ply,,,\nA,2,a2.ply,,,\n"
                        "B,T1,b1.ply,,,\nB,T0,b0.ply,,,\n"
                        "C,0,c0.ply,,,\nC,1,c1.ply,,\"sphere:2,-1,8.8,5\",\n")
    work = tmp_path_factory.mktemp("results")
    command = ["snakemake", "-s", str(WORKFLOW / "Snakefile"), "-d", str(work), "-j2", "--quiet",
               "--config", f"manifest={manifest}", f"glint={GLINT}", *SMALL]
    done = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, (done.stdout, done.stderr)
    again = subprocess.run([*command, "--dry-run"], capture_output=True, text=True, timeout=120)
    return work, manifest, command, again


def table(work):
    with (work / "cohort.csv").open(newline="") as f:
        return list(csv.DictReader(f))


def test_one_row_per_pair_of_consecutive_time_points(cohort_run):
    rows = table(cohort_run[0])
    assert [(r["subject"], r["before"], r["after"]) for r in rows] == [
        ("A", "0", "1"), ("A", "1", "2"), ("B", "T0", "T1"), ("C", "0", "1")]


def test_table_numbers_are_the_reports(cohort_run):
    work = cohort_run[0]
    for row in table(work):
        report = json.loads((work / row["report"]).read_text())
        regions = report["zooms"][0]["regions"]
        assert int(row["regions"]) == len(regions)
        assert int(row["dents"]) == sum(r["kind"] == "dent" for r in regions)
        assert int(row["bumps"]) == sum(r["kind"] == "bump" for r in regions)
        assert float(row["area_mm2"]) == pytest.approx(sum(r["area"] for r in regions))
        # (a missing-surface region has no depth or volume: null)
        volumes = [r["volume"] for r in regions if r["volume"] is not None]
        depths = [r["peak_depth"] for r in regions if r["peak_depth"] is not None]
        assert float(row["volume_lost_mm3"]) == pytest.approx(-sum(min(v, 0) for v in volumes))
        assert float(row["volume_gained_mm3"]) == pytest.approx(sum(max(v, 0) for v in volumes))
        assert float(row["max_depth_mm"]) == pytest.approx(-min(depths + [0]))
        assert float(row["coverage"]) == pytest.approx(report["zooms"][0]["coverage"])
        assert float(row["fit_rms_mm"]) == pytest.approx(report["fit"]["rms"])
        assert row["fit_converged"] == "True" and row["unit"] == "mm"


def test_table_finds_the_damage_that_was_made(cohort_run):
    a01, a12, b, c = table(cohort_run[0])
    # A 0→1: the 0.6 mm dent appeared.
    assert (a01["regions"], a01["dents"]) == ("1", "1")
    assert 0.4 < float(a01["max_depth_mm"]) < 0.7 and float(a01["volume_lost_mm3"]) > 0
    # A 1→2: the dent was already there; only the 0.5 mm bump is new.
    assert (a12["regions"], a12["bumps"], a12["dents"]) == ("1", "1", "0")
    assert 0.3 < float(a12["max_height_mm"]) < 0.6 and float(a12["volume_gained_mm3"]) > 0
    # B: nothing changed.
    assert b["regions"] == "0" and float(b["volume_lost_mm3"]) == 0 and float(b["volume_gained_mm3"]) == 0
    # C: the bump lies outside the analysed region.
    assert (c["regions"], c["dents"], c["bumps"]) == ("1", "1", "0")
    for row in (a01, a12, b, c):
        assert float(row["fit_rms_mm"]) < 0.05 and float(row["coverage"]) > 0.9


def test_length_columns_carry_the_reports_unit(cohort_run):
    with (cohort_run[0] / "cohort.csv").open(newline="") as f:
        header = next(csv.reader(f))
    assert [c for c in header if c.split("_")[-1] in ("mm", "mm2", "mm3")] == [
        "area_mm2", "volume_lost_mm3", "volume_gained_mm3", "max_depth_mm", "max_height_mm", "fit_rms_mm"]
    # cohort.json keeps the plain names (the summary reads them) and each row's unit.
    assert {"area", "volume_lost", "unit"} <= json.loads((cohort_run[0] / "cohort.json").read_text())[0].keys()


def _row(subject, unit, error=""):
    row = dict.fromkeys(cohort.TABLE_COLUMNS, 1.0)
    row.update(subject=subject, before="0", after="1", unit=unit, error=error)
    return row


def test_a_cohort_in_another_unit_gets_that_unit(tmp_path):
    rows = [_row("A", "um"), _row("B", None, error="glint: error: refused")]
    cohort.write_table(rows, tmp_path / "c.csv", tmp_path / "c.json")
    header = (tmp_path / "c.csv").read_text().splitlines()[0].split(",")
    assert {"area_um2", "volume_lost_um3", "max_depth_um", "fit_rms_um"} <= set(header)
    cohort.write_table([_row("A", "")], tmp_path / "d.csv", tmp_path / "d.json")
    assert "area_units2" in (tmp_path / "d.csv").read_text().splitlines()[0].split(",")


def test_pairs_in_different_units_are_refused_naming_them(tmp_path):
    with pytest.raises(cohort.UnitError, match=r"A 0→1 in mm, B 0→1 in um\); expected one unit"):
        cohort.write_table([_row("A", "mm"), _row("B", "um")], tmp_path / "c.csv", tmp_path / "c.json")
    assert not (tmp_path / "c.csv").exists() and not (tmp_path / "c.json").exists()


def test_summary_files(cohort_run):
    work = cohort_run[0]
    png = (work / "cohort.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
    page = (work / "cohort.html").read_text()
    assert 'src="cohort.png"' in page
    for row in table(work):
        assert f'href="{pathlib.PurePosixPath(row["report"])}"' in page
    assert json.loads((work / "cohort.json").read_text())[0]["subject"] == "A"


def test_cohort_colours_are_the_atlas_colours():
    """cohort.png draws loss and gain in the colours every atlas picture gives them: the ends of
    the diverging map (blue = loss, red = gain), read from the C++ table the pictures use."""
    canvas = (SOURCE / "image" / "diverging_knots.h").read_text()
    table = canvas[canvas.index("kDivergingKnots = {"):]
    knots = [line.split("//")[1].strip() for line in table[:table.index("};")].splitlines() if "//" in line]
    assert (summary.LOSS_COLOUR, summary.GAIN_COLOUR) == (knots[0], knots[-1])


def test_a_second_run_has_nothing_to_do(cohort_run):
    again = cohort_run[3]
    assert again.returncode == 0 and "Nothing to be done" in again.stdout + again.stderr


def test_manifest_problems_name_row_and_column(tmp_path):
    (tmp_path / "scan.ply").write_text("")
    bad = tmp_path / "m.csv"
    bad.write_text("subject,time,path\nA,0,scan.ply\n")
    with pytest.raises(cohort.ManifestError, match="lacks timepoint"):
        cohort.read_manifest(bad)
    bad.write_text("subject,timepoint,path\nA,0,scan.ply\nA,0,scan.ply\n")
    with pytest.raises(cohort.ManifestError, match="row 3: subject A time point 0 already on row 2"):
        cohort.read_manifest(bad)
    bad.write_text("subject,timepoint,path\nA,0,missing.ply\n")
    with pytest.raises(cohort.ManifestError, match="row 2: path .*missing.ply: not found"):
        cohort.read_manifest(bad)
    bad.write_text("subject,timepoint,path,iso\nA,0,scan.ply,bone\n")
    with pytest.raises(cohort.ManifestError, match="row 2: iso \"bone\": expected a number"):
        cohort.read_manifest(bad)
    bad.write_text("subject,timepoint,path,iso\nA,0,scan.ply,300\nA,1,scan.ply,250\n")
    with pytest.raises(cohort.ManifestError, match="different iso values"):
        cohort.pairs(cohort.read_manifest(bad))


def test_volumes_get_their_iso_value(tmp_path, cohort_run):
    (tmp_path / "ct0.nii.gz").write_text("")
    (tmp_path / "ct1.nii.gz").write_text("")
    manifest = tmp_path / "m.csv"
    manifest.write_text("subject,timepoint,path,iso\nP,0,ct0.nii.gz,300\nP,1,ct1.nii.gz,300\n")
    command = cohort_run[2]
    at = command.index("--config")
    dry = [*(a for a in command[:at] if a != "--quiet"), "--dry-run", "--printshellcmds", "-d",
           str(tmp_path / "out"), "--config", f"manifest={manifest}", *command[at + 2:]]
    done = subprocess.run(dry, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "--iso 300" in done.stdout and "ct0.nii.gz" in done.stdout


def test_snakemake_reports_a_bad_manifest(tmp_path, cohort_run):
    manifest = tmp_path / "m.csv"
    manifest.write_text("subject,timepoint\nA,0\n")
    command = cohort_run[2]
    at = command.index("--config")
    done = subprocess.run([*command[:at], "-d", str(tmp_path / "out"), "--config", f"manifest={manifest}",
                           *command[at + 2:]], capture_output=True, text=True, timeout=120)
    assert done.returncode != 0 and "lacks path" in done.stdout + done.stderr


def test_a_relative_profile_path_is_refused_before_any_job(tmp_path, cohort_run):
    # Snakemake 7 would find the Slurm profile's status script from here, then look for it from
    # the results folder after submitting the jobs; the workflow stops first and says how.
    manifest = cohort_run[1]
    command = ["snakemake", "-s", str(WORKFLOW / "Snakefile"), "-d", str(tmp_path / "out"), "--dry-run",
               "--profile", "workflows/cohort/profiles/slurm", "--config", f"manifest={manifest}"]
    done = subprocess.run(command, cwd=SOURCE, env=dict(os.environ, PWD=str(SOURCE)), capture_output=True,
                          text=True, timeout=120)
    assert done.returncode != 0
    assert 'give the profile as an absolute path (--profile "$PWD/workflows/cohort/profiles/slurm")' in done.stdout + done.stderr
    absolute = [a if a != "workflows/cohort/profiles/slurm" else str(WORKFLOW / "profiles" / "slurm") for a in command]
    done = subprocess.run(absolute, cwd=SOURCE, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "rule sweep" in done.stdout  # the same call with the absolute path goes on


def test_a_pair_glint_refuses_gets_its_reason_in_the_table(tmp_path, cohort_run):
    # The header promises three vertices and none follow: glint exits 2 with one line. That pair's
    # row carries the line; the other pair completes; the run succeeds and names the refused pair.
    manifest, command = cohort_run[1], cohort_run[2]
    (tmp_path / "cut.ply").write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nend_header\n")
    bad = tmp_path / "m.csv"
    scans = manifest.parent
    bad.write_text(f"subject,timepoint,path\nA,0,{scans}/a0.ply\nA,1,{scans}/a1.ply\nX,0,{scans}/a0.ply\n"
                   f"X,1,{tmp_path}/cut.ply\n")
    at = command.index("--config")
    done = subprocess.run([*(a for a in command[:at] if a != "--quiet"), "-d", str(tmp_path / "out"), "--config",
                           f"manifest={bad}", *command[at + 2:]], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    good, refused = table(tmp_path / "out")
    assert good["error"] == "" and good["regions"] == "1"
    assert refused["error"].startswith('glint: error: mesh "') and "cut.ply" in refused["error"]
    assert refused["regions"] == refused["report"] == ""
    assert (tmp_path / "out" / "pairs" / "X" / "0_to_1" / "error.txt").read_text().strip() == refused["error"]
    assert "glint refused the input of 1 of 2 pair(s)" in done.stderr
    assert 'href="logs/X/0_to_1.log"' in (tmp_path / "out" / "cohort.html").read_text()


def made_up_rows():
    """Table rows as cohort.py makes them: three pairs swept, one refused, wide enough text to
    need more than 800 px."""
    swept = dict.fromkeys(cohort.TABLE_COLUMNS, 0)
    swept.update(regions=2, dents=1, bumps=1, area=41.23, volume_lost=3.456, volume_gained=2.01, max_depth=0.58,
                 max_height=0.39, coverage=0.987, fit_converged=True, fit_rms=0.0123, fit_inlier_fraction=0.99,
                 fit_overlap=0.998, fit_rotation_deg=12.5, fit_termination="rotation and translation steps below "
                 "tolerance", unit="mm", error="")
    rows = [dict(swept, subject=s, before="0", after="1", report=f"pairs/{s}/0_to_1/report.json") for s in "ABC"]
    rows[1].update(regions=0, dents=0, bumps=0)
    refused = dict.fromkeys(cohort.TABLE_COLUMNS)
    refused.update(subject="X", before="0", after="1", report="", error='glint: error: mesh "cut.ply": no vertices')
    return rows + [refused]


def test_cohort_page_has_the_report_style_units_and_a_banner(tmp_path):
    rows = made_up_rows()
    summary.write_html(rows, cohort.TABLE_COLUMNS, tmp_path / "cohort.html", "cohort.png")
    page = (tmp_path / "cohort.html").read_text()
    # One style: report.html's glint.css (the one the build embeds), inlined whole.
    assert summary_html.STYLE_PATH == (SOURCE / "report" / "html" / "glint.css").resolve()
    assert summary_html.STYLE_PATH.read_text() in page
    for heading in ("area (mm²)", "volume lost (mm³)", "max depth (mm)", "fit rms (mm)", "fit rotation (°)",
                    "coverage (fraction)"):
        assert f">{heading}</th>" in page, heading
    assert '<div class="table-scroll"><table id="cohort" class="data">' in page
    assert '<p id="verdict">4 pairs: 2 with regions, 1 without, 1 refused</p>' in page
    assert '<li class="severe">X 0 → 1: glint refused the input: glint: error: mesh &quot;cut.ply&quot;' in page
    assert 'href="pairs/A/0_to_1/report.html"' in page and 'href="logs/X/0_to_1.log"' in page


def test_header_labels_show_a_unit_the_column_name_carries():
    assert summary_html.header_label("area_mm2", "mm") == "area (mm²)"
    assert summary_html.header_label("volume_lost_mm3", "mm") == "volume lost (mm³)"
    assert summary_html.header_label("max_depth_mm", "mm") == "max depth (mm)"
    assert summary_html.header_label("fit_rotation_deg", "") == "fit rotation (°)"
    assert summary_html.header_label("dents", "mm") == "dents"


def test_cohort_table_scrolls_in_its_box_not_the_page(tmp_path):
    """In headless Chromium at 800 px: the page is no wider than the window, the table's box
    scrolls sideways, and the header row sticks."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if not chromium:
        pytest.skip("no chromium (Debian package chromium)")
    websocket = pytest.importorskip("websocket", reason="Debian package python3-websocket")  # noqa: F841
    sys.path.insert(0, str(SOURCE / "tests" / "tools"))
    from report_html_check import DevTools, start_chromium

    summary.write_html(made_up_rows(), cohort.TABLE_COLUMNS, tmp_path / "cohort.html", "cohort.png")
    profile = tmp_path / "profile"
    profile.mkdir()
    proc, url = start_chromium(chromium, str(profile))
    try:
        dt = DevTools(url)
        dt.call("Page.enable")
        dt.call("Emulation.setDeviceMetricsOverride", width=800, height=700, deviceScaleFactor=1, mobile=False)
        dt.call("Page.navigate", url=(tmp_path / "cohort.html").as_uri())
        measure = """(() => { const d = document.documentElement, box = document.querySelector('.table-scroll');
            if (document.readyState !== 'complete' || !box) return null;
            return {page: [d.scrollWidth, d.clientWidth], box: [box.scrollWidth, box.clientWidth],
                    overflow: getComputedStyle(box).overflowX,
                    sticky: getComputedStyle(document.querySelector('#cohort th')).position}; })()"""
        got = None
        for _ in range(100):
            got = dt.evaluate(measure)
            if got:
                break
            time.sleep(0.1)
    finally:
        proc.kill()
        proc.wait()
    assert got, "the page did not load"
    assert got["page"][0] <= got["page"][1], got
    assert got["box"][0] > got["box"][1], got  # wider than the window: it scrolls in its box
    assert got["overflow"] == "auto" and got["sticky"] == "sticky", got


def test_pictures_false_gives_no_picture_flag_and_keeps_views_off():
    pair = {"after": {"iso": "", "roi": "", "landmarks": ""}}
    base = {"size": 64, "azimuth_step": 60, "elevations": [0]}
    default = cohort.sweep_arguments(pair, base)
    assert "--no-views" in default and "--no-pictures" not in default
    without = cohort.sweep_arguments(pair, {**base, "pictures": False})
    assert "--no-pictures" in without and "--no-views" not in without
    # `--config pictures=false views=true` reaches the workflow as text
    assert "--no-pictures" in cohort.sweep_arguments(pair, {**base, "pictures": "false"})
    assert "--no-views" not in cohort.sweep_arguments(pair, {**base, "views": "true"})
    with pytest.raises(ValueError, match="pictures = 'maybe'"):
        cohort.sweep_arguments(pair, {**base, "pictures": "maybe"})


def test_a_cohort_without_pictures_has_the_same_table_and_no_png(tmp_path, cohort_run):
    """pictures=false (issue 25): each pair's glint draws no PNG and loads no image library; the
    cohort table, made from report.json, is the same as with pictures."""
    work, manifest, command, _ = cohort_run
    at = command.index("--config")
    out = tmp_path / "out"
    done = subprocess.run([*command[:at], "-d", str(out), *command[at:], "pictures=false"],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, (done.stdout, done.stderr)
    assert not list((out / "pairs").rglob("*.png"))
    assert list((work / "pairs").rglob("*.png")), "the run with pictures drew none"
    drop = {"report"}  # the path of each pair's report differs between the two result folders
    strip = lambda rows: [{k: v for k, v in r.items() if k not in drop} for r in rows]  # noqa: E731
    assert strip(table(out)) == strip(table(work))
