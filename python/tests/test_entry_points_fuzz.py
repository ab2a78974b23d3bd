"""Issue 23: the Python entry points under hostile input. entry_point_cases.py feeds seeded
mutations of small valid files (mesh formats, a volume, a fit file) to glint.load, and hostile
values (NaN, inf, huge, negative, wrong types, control bytes, /dev/zero) to load's keywords,
options(), as_mesh(), Mesh.transform(), asymmetry(), register() and analyse(). It runs in a
child interpreter: a crash of the module ends that child with a signal, which fails here naming
the case. Every case either works or raises glint's own error (one line) or a TypeError from
the argument conversion (a ValueError where numpy cannot convert a value), never another kind."""
import json
import os
import pathlib
import subprocess
import sys

import pytest

DRIVER = pathlib.Path(__file__).with_name("entry_point_cases.py")
ALLOWED = {"InputError", "IoError", "DeviceError", "TypeError", "ValueError"}


@pytest.mark.parametrize("seed", [1, 2])
def test_hostile_inputs_never_crash_and_every_error_is_one_line(seed, glint_exe, test_data, tmp_path):
    run = subprocess.run([sys.executable, str(DRIVER), str(seed), str(tmp_path), str(glint_exe),
                          str(test_data)], capture_output=True, text=True, timeout=240,
                         env=dict(os.environ))
    lines = [json.loads(line) for line in run.stdout.splitlines() if line.startswith("{")]
    started = [line["start"] for line in lines if "start" in line]
    records = [line for line in lines if "outcome" in line]
    assert run.returncode == 0, (
        f"the interpreter ended with {run.returncode} in case {started[-1] if started else '?'} "
        f"({records[-1]['call'] if records else 'before any case'} was the last that ended): "
        f"{run.stderr[-2000:]}")
    assert len(records) == len(started) and len(records) > 300
    bad = [r for r in records if r["outcome"] == "raised" and
           (r["type"] not in ALLOWED or (r["type"] != "TypeError" and "\n" in r["message"]))]
    assert not bad, "\n".join(f"{r['call']}: {r['type']}: {r['message'][:300]!r}" for r in bad[:10])
    # The cases reach past the argument checks: some work, many are refused by glint itself.
    assert sum(r["outcome"] == "ok" for r in records) >= 10
    assert sum(r.get("glint_error", False) for r in records) >= 100
