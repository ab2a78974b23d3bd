#!/usr/bin/env python3
"""Issue 26: progress through every stage of a sweep, on a terminal only, and --quiet that
silences progress but never the results.

glint runs under a pseudo-terminal (pty), as it does in a user's shell; stdout and stderr both go
to the terminal, as they do there. The stream is cut into what each redraw shows (at '\\r' and
'\\n') and checked:

  - every stage is named: load, fit, distance, sweep, decide, export and each export (atlas
    files, report page, pictures, mosaics, atlas.png, report.html), in that order;
  - every export's line comes after the last sweep line (the exports are no longer silent behind
    a finished sweep bar);
  - a counted stage shows an ETA while it runs, and every stage the seconds it took;
  - with --quiet: no stage line, but the results summary;
  - with stderr no terminal: no progress at all on stderr.

  progress_test.py GLINT WORKDIR
"""
import os
import pty
import re
import shutil
import subprocess
import sys

GLINT, WORK = sys.argv[1], sys.argv[2]
CUBE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "cube.obj")
# --views: a picture per view, so that the pictures stage has a count to show.
SMALL = ["--size", "32", "--azimuth-step", "90", "--elevations", "0,45", "--no-exr", "--views"]
STAGES = ["load", "fit", "distance", "sweep", "decide", "export", "atlas files", "report page",
          "pictures", "mosaics", "atlas.png", "report.html"]
EXPORTS = STAGES[STAGES.index("export"):]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def in_terminal(args):
    """glint's exit code and everything it wrote, run with a pty as stdin, stdout and stderr."""
    main, side = pty.openpty()
    child = subprocess.Popen([GLINT, *args], stdin=side, stdout=side, stderr=side, close_fds=True)
    os.close(side)
    chunks = []
    while True:
        try:
            chunk = os.read(main, 65536)
        except OSError:  # EIO: every writer closed the terminal
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(main)
    return child.wait(timeout=300), b"".join(chunks).decode("utf-8", "replace")


def shown(stream):
    """What each redraw left on the line: the stream cut at carriage returns and newlines, the
    clear-to-end-of-line escape removed."""
    return [s for s in re.split(r"[\r\n]+", stream.replace("\x1b[K", "")) if s.strip()]


def stage_of(segment):
    """The stage a progress line names (the longest name that starts it and ends at a space)."""
    named = [s for s in STAGES if segment == s or segment.startswith(s + " ")]
    return max(named, key=len) if named else None


def sweep(name, *flags):
    out = os.path.join(WORK, name)
    return [*flags, "sweep", CUBE, CUBE, *SMALL, "--force", "-o", out]


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

# On a terminal: every stage, in order, the exports after the sweep.
code, stream = in_terminal(sweep("tty"))
check(code == 0, f"sweep on a terminal: exit {code}\n{stream}")
segments = shown(stream)
stages = [(i, stage_of(s)) for i, s in enumerate(segments) if stage_of(s)]
first = {}
for i, s in stages:
    first.setdefault(s, i)
check(list(first) == STAGES, f"stages named, in their order: {list(first)}; expected {STAGES}")
last_sweep = max((i for i, s in stages if s == "sweep"), default=-1)
check(all(i > last_sweep for i, s in stages if s in EXPORTS),
      "an export's line comes before the last sweep line")
check(any(stage_of(s) == "sweep" and " eta " in s for s in segments) or
      any(stage_of(s) == "sweep" and "took" in s for s in segments), "the sweep line has no ETA")
check(any(stage_of(s) == "pictures" and re.search(r"\d+/\d+", s) for s in segments),
      "the per-view pictures are not counted")
for name in STAGES:
    check(any(stage_of(s) == name and "took" in s for s in segments),
          f"stage {name}: no line with the time it took")
check(any("views in" in s for s in segments), "the results summary is missing")

# --quiet on a terminal: results, no progress.
code, stream = in_terminal(sweep("quiet", "--quiet"))
check(code == 0, f"--quiet sweep: exit {code}\n{stream}")
segments = shown(stream)
check(not [s for s in segments if stage_of(s)],
      f"--quiet shows progress: {[s for s in segments if stage_of(s)][:3]}")
check(any(s.startswith("zoom 0: footprint") for s in segments) and
      any("views in" in s for s in segments), f"--quiet hides the results summary:\n{stream}")

# stderr no terminal: no progress on it (results on stdout as ever).
done = subprocess.run([GLINT, *sweep("pipe")], capture_output=True, text=True, timeout=300)
check(done.returncode == 0, f"piped sweep: exit {done.returncode}: {done.stderr}")
check("\r" not in done.stderr and not [s for s in shown(done.stderr) if stage_of(s)],
      f"progress on a stderr that is no terminal: {done.stderr[:200]!r}")
check("views in" in done.stdout, "piped sweep: no results summary")

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
