#!/usr/bin/env python3
"""The five front ends of the option registry agree (analysis/option_registry.h).

Every option `glint options --json` lists must be reachable, with the same default and the same
meaning, through each front end, each exercised through its own interface:

  command line   glint sweep … --<flag> … --print-options
  scenario TOML  glint run scenario.toml --print-options
  Python         glint.options(**keywords), and help(glint.analyse) documents every keyword
  3D Slicer      glint --xml (defaults) and a Slicer-style call with --print-options
  JSON           what --print-options prints (report.json's "analysis")

Twice: with nothing set (the defaults), and with every option set to a value other than its
default (so an option that a front end ignores, or binds to another field, shows).

  option_front_ends_test.py GLINT WORKDIR [PYTHONPATH]
"""
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

GLINT, WORK = sys.argv[1], sys.argv[2]
PYPATH = sys.argv[3] if len(sys.argv) > 3 else ""
os.makedirs(WORK, exist_ok=True)
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def run(*args):
    done = subprocess.run([GLINT, *args], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"glint {' '.join(args)}: exit {done.returncode}\n{done.stderr}")
    return done.stdout


def text(value):
    """A value as the registry spells it (option_text in analysis/option_registry.cpp)."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return f"{value:.10g}"
    if isinstance(value, list):
        return ",".join(f"{v:.10g}" for v in value)
    return str(value)


def at(tree, option):
    section, key = option["toml"].rsplit(".", 1) if "." in option["toml"] else ("", option["toml"])
    return (tree.get(section, {}) if section else tree).get(key, "<absent>")


registry = json.loads(run("--json", "options"))
analysis = [o for o in registry if o["group"] != "exports"]
check(len(registry) >= 40, f"the registry lists {len(registry)} options")
cube = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "cube.obj")


def chosen(o):
    """A valid value other than the default, of the option's kind."""
    special = {"plan": "sphere:12", "device": "llvmpipe", "atlas_formats": "ply,vtp",
               "fit_roi": "sphere:0,0,0,5", "roi": "box:-1,-1,-1,1,1,1",
               "landmarks": os.path.join(WORK, "landmarks.json"), "init": os.path.join(WORK, "init.json")}
    if o["name"] in special:
        return special[o["name"]]
    kind, lo, hi = o["kind"], o["min"], o["max"]
    if kind == "flag":
        return o["default"] != "true"
    if kind == "choice":
        return next(c for c in o["choices"] if c != o["default"])
    if kind == "integer":
        return int(lo + (hi - lo) * 0.37) if hi is not None else int(lo) + 3
    if kind in ("number", "optional number"):
        if lo is not None and hi is not None:
            return round(lo + (hi - lo) * 0.37, 3)
        return round((lo if lo is not None else 0.0) + 1.5, 3)
    if kind == "numbers":
        if lo is not None and hi is not None:
            return [round(lo + (hi - lo) * 0.2, 3), round(lo + (hi - lo) * 0.6, 3)]
        return [0.5, 1.5]
    raise SystemExit(f"no test value for {o['name']} ({kind})")


values = {o["name"]: chosen(o) for o in registry}

# --- the defaults -------------------------------------------------------------------------
cli_defaults = json.loads(run("sweep", cube, cube, "-o", os.path.join(WORK, "unused"), "--print-options"))
for o in registry:
    check(text(at(cli_defaults, o)) == o["default"],
          f"JSON default of {o['toml']}: {text(at(cli_defaults, o))!r}, registry {o['default']!r}")
scenario = os.path.join(WORK, "defaults.toml")
with open(scenario, "w") as f:
    f.write(f'[reference]\nmesh = "{cube}"\n')
toml_defaults = json.loads(run("run", scenario, "-o", os.path.join(WORK, "unused"), "--print-options"))
for tree in (cli_defaults, toml_defaults):
    tree["registration"].pop("mode")  # how the pair is fitted: each front end's own default
check(toml_defaults == cli_defaults, "scenario defaults differ from the command line's")

help_text = run("sweep", "--help")
for o in registry:
    check(o["flag"] in help_text, f"glint sweep --help does not list {o['flag']}")

xml = ET.fromstring(run("--xml"))
slicer = {p.findtext("name"): p for group in xml.findall("parameters") for p in group}
for o in analysis:
    name = o["slicer"]
    if o["kind"] == "flag" and o["default"] == "true":
        name = "no" + name[0].upper() + name[1:]  # Slicer passes booleans only when true
    p = slicer.get(name)
    check(p is not None, f"the Slicer module has no parameter {name} for {o['name']}")
    if p is None:
        continue
    default = p.findtext("default") or ""
    want = {"flag": "false"}.get(o["kind"], o["default"])
    if o["kind"] == "optional number" and o["default"] == "":
        want = "0"
    if o["kind"] == "choice" and o["default"] == "":
        want = "auto"
    check(default == want, f"Slicer default of {name}: {default!r}, expected {want!r}")

def python_literal(o):
    """The registry's default text as help(glint.analyse) writes it: a Python literal."""
    text, kind = o["default"], o["kind"]
    if kind == "flag":
        return "True" if text == "true" else "False"
    if kind == "numbers":
        return "[" + ", ".join(text.split(",")) + "]"
    if kind in ("choice", "text", "region", "path"):
        return repr(text)
    return text


python_defaults = None
if PYPATH:
    sys.path.insert(0, PYPATH)
    import glint  # noqa: E402

    python_defaults = glint.options()
    python_defaults["registration"].pop("mode", None)
    compare = dict(cli_defaults)
    check({k: v for k, v in python_defaults.items() if k != "registration"} ==
          {k: v for k, v in compare.items() if k != "registration"},
          "glint.options() defaults differ from the command line's")
    doc = glint.analyse.__doc__
    for o in registry:
        line = next((l for l in doc.splitlines() if l.strip().startswith(o["name"] + ":")), None)
        check(line is not None, f"help(glint.analyse) does not document {o['name']}")
        if line and o["default"]:
            check(f"= {python_literal(o)}" in line, f"help(glint.analyse) gives {o['name']} no default: {line}")
        if line and o["unit"]:
            check(f"[{o['unit']}]" in line, f"help(glint.analyse) gives {o['name']} no unit: {line}")

# --- every option set to another value -----------------------------------------------------
def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(repr(x) for x in v) + "]"
    return json.dumps(v)


def resolve_everywhere(chosen_options, label):
    """Sets the chosen options to their test values through each front end; all must agree."""
    names = {o["name"] for o in chosen_options}
    cli_args = []
    for o in chosen_options:
        v = values[o["name"]]
        if o["kind"] == "flag":
            cli_args.append(o["flag"] if v else "--no-" + o["flag"][2:])
        else:
            cli_args += [o["flag"], text(v)]
    cli = json.loads(run("sweep", cube, cube, "-o", os.path.join(WORK, "unused"), "--register",
                         *cli_args, "--print-options"))
    for o in registry:
        want = text(values[o["name"]]) if o["name"] in names else o["default"]
        check(text(at(cli, o)) == want,
              f"{label}: {o['flag']} gave {o['toml']} = {text(at(cli, o))!r}, expected {want!r}")
    cli["registration"].pop("mode")

    sections = {}
    for o in chosen_options:
        section, key = o["toml"].rsplit(".", 1) if "." in o["toml"] else ("", o["toml"])
        sections.setdefault(section, []).append(f"{key} = {toml_value(values[o['name']])}")
    with open(scenario, "w") as f:
        f.write("\n".join(sections.pop("", [])) + "\n")
        f.write(f'[reference]\nmesh = "{cube}"\n')
        for section, lines in sections.items():
            f.write(f"[{section}]\n" + "\n".join(lines) + "\n")
    toml = json.loads(run("run", scenario, "-o", os.path.join(WORK, "unused"), "--print-options"))
    toml["registration"].pop("mode")
    check(toml == cli, f"{label}: the scenario resolves differently from the flags:\n"
          f"{json.dumps(toml, sort_keys=True)}\n{json.dumps(cli, sort_keys=True)}")

    # The Slicer module and glint.options() set the exports their own way (their own output).
    cli_analysis = {k: v for k, v in cli.items() if k != "exports"}
    slicer_args = ["--returnparameterfile", os.path.join(WORK, "r.params")]
    for o in chosen_options:
        if o["group"] == "exports":
            continue
        v = values[o["name"]]
        if o["kind"] == "flag":
            name = o["slicer"] if v else "no" + o["slicer"][0].upper() + o["slicer"][1:]
            slicer_args.append("--" + name)
        else:
            slicer_args += ["--" + o["slicer"], text(v)]
    slicer_call = json.loads(run(*slicer_args, "--register", "--print-options", cube, cube,
                                 os.path.join(WORK, "atlas.vtp")))
    slicer_call["registration"].pop("mode")
    slicer_call.pop("exports")
    if "unit" not in names:
        slicer_call["unit"] = cli["unit"]  # Slicer's models are in mm: its unit when none is given
    check(slicer_call == cli_analysis,
          f"{label}: the Slicer call resolves differently from the flags:\n"
          f"{json.dumps(slicer_call, sort_keys=True)}\n{json.dumps(cli_analysis, sort_keys=True)}")

    if PYPATH:
        py = glint.options(**{o["name"]: values[o["name"]] for o in chosen_options}, register=True)
        py["registration"].pop("mode", None)
        py.pop("exports")
        check(py == cli_analysis,
              f"{label}: glint.options() resolves differently from the flags:\n"
              f"{json.dumps(py, sort_keys=True)}\n{json.dumps(cli_analysis, sort_keys=True)}")


# note: landmarks and an initial pose both set the starting pose, so they go in two passes.
resolve_everywhere([o for o in registry if o["name"] != "init"], "every option but init")
resolve_everywhere([o for o in registry if o["name"] == "init"], "init")

for f in failures:
    print("FAIL:", f)
if failures:
    sys.exit(1)
print(f"ok: {len(registry)} options agree across the command line, scenario files, "
      f"{'Python, ' if PYPATH else ''}the Slicer module and the JSON, defaults and set values")
