"""The cohort workflow's logic (the Snakefile only wires it): the manifest, the pairs of
consecutive time points, the cohort table read from each pair's report.json, the summary.

Manifest (CSV, header required, one row per scan):
    subject,timepoint,path[,iso][,roi][,landmarks]
  subject    an identifier (letters, digits, '-', '_', '.')
  timepoint  ordered numerically when every time point of the cohort is a number, else as
             text (ISO dates, T0 < T1 …); same characters as subject
  path       a mesh file or a volume (file or DICOM folder); relative to the manifest's folder
  iso        the iso value when path is a volume (both scans of a pair must agree)
  roi        analyse only this part of the surface (glint's sphere:x,y,z,r / box:…) for the pair
             that ends at this row
  landmarks  landmark pairs (JSON, glint register --landmarks) starting the fit of the pair that
             ends at this row
Each subject's consecutive time points make one pair; `glint sweep --register` runs once per
pair (one process per pair), the earlier scan as the reference. A pair whose input glint refuses
(exit code 2: a file it cannot read, a mesh without triangles, an option it rejects) gets a
folder holding only error.txt, glint's one-line reason, and a table row with that reason in
`error` and no numbers.
"""
import csv
import json
import os
import pathlib
import re

COLUMNS = ("subject", "timepoint", "path", "iso", "roi", "landmarks")
REQUIRED = ("subject", "timepoint", "path")
_IDENT = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]*$")


class ManifestError(ValueError):
    """A manifest problem, one line naming the file, the row and the column."""


class ProfileError(ValueError):
    """A Snakemake profile given in a way this workflow cannot use, and how to give it."""


def lost_profile(argv, environ):
    """The profile folder given to snakemake as a relative path (--profile or SNAKEMAKE_PROFILE)
    that this process no longer sees from the results folder it changed into (-d), or None.

    note: Snakemake 7 resolves the profile's status script against the folder it was started in
    and then changes into -d; from there the script's relative path names nothing, and the first
    status check, after the jobs are submitted, fails. The Snakefile stops before that."""
    profile = environ.get("SNAKEMAKE_PROFILE", "")
    for i, arg in enumerate(argv):
        if arg == "--profile" and i + 1 < len(argv):
            profile = argv[i + 1]
        elif arg.startswith("--profile="):
            profile = arg.split("=", 1)[1]
    start = environ.get("PWD", "")  # the shell's folder: os.chdir leaves PWD as it was
    if not profile or os.path.isabs(profile) or not start:
        return None
    was_path = os.path.isdir(os.path.join(start, profile))  # else a name, found in ~/.config/snakemake
    return profile if was_path and not os.path.isdir(profile) else None


def _number(text):
    try:
        return float(text)
    except ValueError:
        return None


def read_manifest(path):
    """The manifest's rows as dicts (paths made absolute), sorted by subject and time point.
    Raises ManifestError naming the file, row and column of the first problem."""
    path = pathlib.Path(path)
    if not path.is_file():
        raise ManifestError(f"manifest {path}: file not found")
    base = path.resolve().parent
    with path.open(newline="") as f:
        reader = csv.DictReader(f)
        header = [h.strip() for h in (reader.fieldnames or [])]
        missing = [c for c in REQUIRED if c not in header]
        if missing:
            raise ManifestError(f"manifest {path}: header {','.join(header) or '(empty)'} lacks "
                                f"{', '.join(missing)}; expected {','.join(COLUMNS)} (iso, roi, landmarks optional)")
        unknown = [c for c in header if c not in COLUMNS]
        if unknown:
            raise ManifestError(f"manifest {path}: unknown column {unknown[0]}; expected {','.join(COLUMNS)}")
        rows = []
        for line, raw in enumerate(reader, start=2):
            row = {k.strip(): (v or "").strip() for k, v in raw.items() if k is not None}
            rows.append(_check_row(path, base, line, row))
    if not rows:
        raise ManifestError(f"manifest {path}: no rows")
    seen = {}
    for r in rows:
        key = (r["subject"], r["timepoint"])
        if key in seen:
            raise ManifestError(f"manifest {path}: row {r['line']}: subject {key[0]} time point {key[1]} "
                                f"already on row {seen[key]}")
        seen[key] = r["line"]
    numeric = all(_number(r["timepoint"]) is not None for r in rows)
    return sorted(rows, key=lambda r: (r["subject"], _number(r["timepoint"]) if numeric else r["timepoint"]))


def _check_row(path, base, line, row):
    where = f"manifest {path}: row {line}"
    for column in ("subject", "timepoint"):
        if not _IDENT.match(row.get(column, "")):
            raise ManifestError(f"{where}: {column} \"{row.get(column, '')}\": expected letters, digits, '.', '-', '_'")
    if not row.get("path"):
        raise ManifestError(f"{where}: path is empty")
    scan = pathlib.Path(row["path"])
    scan = scan if scan.is_absolute() else base / scan
    if not scan.exists():
        raise ManifestError(f"{where}: path {scan}: not found")
    iso = row.get("iso", "")
    if iso and _number(iso) is None:
        raise ManifestError(f"{where}: iso \"{iso}\": expected a number")
    landmarks = row.get("landmarks", "")
    if landmarks:
        lm = pathlib.Path(landmarks)
        lm = lm if lm.is_absolute() else base / lm
        if not lm.is_file():
            raise ManifestError(f"{where}: landmarks {lm}: not found")
        landmarks = str(lm)
    return {"subject": row["subject"], "timepoint": row["timepoint"], "path": str(scan), "iso": iso,
            "roi": row.get("roi", ""), "landmarks": landmarks, "line": line}


def pairs(rows):
    """Consecutive time points per subject: {pair id: {subject, before, after}} in order.
    A pair id is "<subject>/<t0>_to_<t1>" (the folder of its results)."""
    out = {}
    by_subject = {}
    for r in rows:
        by_subject.setdefault(r["subject"], []).append(r)
    for subject, scans in by_subject.items():
        for before, after in zip(scans, scans[1:]):
            if before["iso"] != after["iso"]:
                raise ManifestError(f"manifest: subject {subject}: time points {before['timepoint']} and "
                                    f"{after['timepoint']} have different iso values ({before['iso'] or 'none'}, "
                                    f"{after['iso'] or 'none'}); one pair is swept at one iso value")
            out[f"{subject}/{before['timepoint']}_to_{after['timepoint']}"] = {
                "subject": subject, "before": before, "after": after}
    return out


def config_flag(config, key, default):
    """A yes/no setting of the config: YAML's true/false, or the text `--config key=false` gives
    (snakemake passes such values as strings, and "false" is a non-empty, true string)."""
    value = config.get(key, default)
    if isinstance(value, str):
        words = {"true": True, "yes": True, "on": True, "1": True,
                 "false": False, "no": False, "off": False, "0": False}
        if value.strip().lower() not in words:
            raise ValueError(f"config {key} = {value!r}: expected true or false")
        return words[value.strip().lower()]
    return bool(value)


def sweep_arguments(pair, config):
    """The `glint sweep` arguments of a pair (after REF EXA), from its rows and the config."""
    args = ["--register", "--size", str(config["size"]), "--azimuth-step", str(config["azimuth_step"]),
            "--elevations", ",".join(str(e) for e in config["elevations"]), "--no-exr"]
    if not config_flag(config, "pictures", True):
        args.append("--no-pictures")  # no PNG at all; the image library is never loaded
    elif not config_flag(config, "views", False):
        args.append("--no-views")
    if config.get("unit"):
        args += ["--unit", str(config["unit"])]
    after = pair["after"]
    if after["iso"]:
        args += ["--iso", after["iso"]]
    if after["roi"]:
        args += ["--roi", after["roi"]]
    if after["landmarks"]:
        args += ["--landmarks", after["landmarks"]]
    args += [str(a) for a in config.get("extra_args", [])]
    return args


TABLE_COLUMNS = ("subject", "before", "after", "regions", "dents", "bumps", "missing_surface", "area",
                 "volume_lost", "volume_gained", "max_depth", "max_height", "coverage", "fit_converged", "fit_rms",
                 "fit_inlier_fraction", "fit_overlap", "fit_rotation_deg", "fit_termination", "unit", "report",
                 "error")
ERROR_FILE = "error.txt"  # in a pair's folder when glint refused its input (the Snakefile writes it)
# The columns that hold a length, by power: cohort.csv's header names their unit (area_mm2,
# volume_lost_mm3, max_depth_mm), the way glint's regions.csv does. cohort.json keeps the plain
# names and the `unit` of each row.
LENGTH_COLUMNS = {"area": 2, "volume_lost": 3, "volume_gained": 3, "max_depth": 1, "max_height": 1, "fit_rms": 1}


class UnitError(ValueError):
    """Pairs whose lengths are in different units: one table column cannot hold them."""


def unit_suffix(unit, power=1):
    """"_mm", "_mm2", "_mm3"; "_units" when glint knew no unit (glint's mesh/units.h unit_suffix)."""
    return "_" + (unit or "units") + (str(power) if power > 1 else "")


def table_unit(rows):
    """The one unit of the cohort's lengths, from each pair's report.json ("" when glint knew none).
    A refused pair has none and does not count. Pairs in different units raise UnitError: a column
    that mixed them would add millimetres to micrometres in every statistic made from it, and one
    column per unit would leave each row's numbers scattered over columns."""
    first = {}
    for r in rows:
        if not r.get("error"):
            first.setdefault(r["unit"] or "", f"{r['subject']} {r['before']}→{r['after']}")
    if len(first) > 1:
        found = ", ".join(f"{pair} in {unit or 'no stated unit'}" for unit, pair in first.items())
        raise UnitError(f"cohort.csv: the pairs' lengths are in different units ({found}); expected one unit "
                        "for the whole cohort: give every scan in one unit (or state it with `unit:` in the "
                        "config when the files state none)")
    return next(iter(first), "")


def table_header(unit):
    """cohort.csv's column names: TABLE_COLUMNS, lengths suffixed with their unit."""
    return [c + unit_suffix(unit, LENGTH_COLUMNS[c]) if c in LENGTH_COLUMNS else c for c in TABLE_COLUMNS]


def pair_row(pair_id, pair, report):
    """One cohort table row from a pair's report.json (zoom 0): lengths in its unit."""
    regions = report["zooms"][0]["regions"]
    depths = [r["peak_depth"] for r in regions if r["peak_depth"] is not None]
    volumes = [r["volume"] for r in regions if r["volume"] is not None]
    fit = report.get("fit") or {}
    return {
        "subject": pair["subject"], "before": pair["before"]["timepoint"], "after": pair["after"]["timepoint"],
        "regions": len(regions),
        "dents": sum(r["kind"] == "dent" for r in regions),
        "bumps": sum(r["kind"] == "bump" for r in regions),
        "missing_surface": sum(r["kind"] == "missing surface" for r in regions),
        "area": sum(r["area"] for r in regions),
        "volume_lost": -sum(v for v in volumes if v < 0),
        "volume_gained": sum(v for v in volumes if v > 0),
        "max_depth": max((-d for d in depths if d < 0), default=0.0),
        "max_height": max([d for d in depths if d > 0], default=0.0),
        "coverage": report["zooms"][0]["coverage"],
        "fit_converged": fit.get("converged"), "fit_rms": fit.get("rms"),
        "fit_inlier_fraction": fit.get("inlier_fraction"), "fit_overlap": fit.get("overlap"),
        "fit_rotation_deg": fit.get("rotation_deg"), "fit_termination": fit.get("termination"),
        "unit": report.get("unit") or "",
        "report": f"pairs/{pair_id}/report.json",
        "error": "",
    }


def error_row(pair, message):
    """The table row of a pair glint refused: who and when, the reason, no numbers."""
    row = dict.fromkeys(TABLE_COLUMNS)
    row.update(subject=pair["subject"], before=pair["before"]["timepoint"], after=pair["after"]["timepoint"],
               report="", error=message)
    return row


def write_table(rows, csv_path, json_path):
    """cohort.csv and cohort.json (written to temporary names, then renamed). Raises UnitError
    (before writing anything) when the pairs' units differ."""
    header = table_header(table_unit(rows))
    csv_path, json_path = pathlib.Path(csv_path), pathlib.Path(json_path)
    tmp = csv_path.with_name(csv_path.name + ".tmp")
    with tmp.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        writer.writerows([row[c] for c in TABLE_COLUMNS] for row in rows)
    tmp.replace(csv_path)
    tmp = json_path.with_name(json_path.name + ".tmp")
    tmp.write_text(json.dumps(rows, indent=2) + "\n")
    tmp.replace(json_path)


def cohort_table(pair_ids, all_pairs, out_dir, csv_path, json_path):
    """Reads every pair's report.json (or its error.txt) and writes the cohort table."""
    rows = []
    for pair_id in pair_ids:
        folder = pathlib.Path(out_dir) / "pairs" / pair_id
        if (folder / ERROR_FILE).is_file():
            rows.append(error_row(all_pairs[pair_id], (folder / ERROR_FILE).read_text().strip()))
        else:
            rows.append(pair_row(pair_id, all_pairs[pair_id], json.loads((folder / "report.json").read_text())))
    write_table(rows, csv_path, json_path)
    return rows


def refused(json_path):
    """The rows of cohort.json whose pair glint refused (empty when there is no table yet)."""
    path = pathlib.Path(json_path)
    return [r for r in json.loads(path.read_text()) if r.get("error")] if path.is_file() else []
