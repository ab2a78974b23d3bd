"""Ctrl-C stops a long glint.analyse: SIGINT to a Python process running one."""
import os
import pathlib
import signal
import subprocess
import sys
import textwrap
import time


SCRIPT = textwrap.dedent("""
    import signal, sys, time
    import glint
    # note: a process started in the background by a non-interactive shell inherits SIGINT
    # ignored, and Python then leaves it so; an interactive Python has this handler.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    ref, exa, out = sys.argv[1:4]
    print("ready", flush=True)
    started = time.monotonic()
    try:
        glint.analyse(ref, exa, output=out, size=384, azimuth_step=5.0,
                      elevations=[-75, -60, -45, -30, -15, 0, 15, 30, 45, 60, 75])
    except KeyboardInterrupt as e:
        print(f"interrupted after {time.monotonic() - started:.2f} s: {e}", flush=True)
        sys.exit(42)
    print("finished", flush=True)
""")


def test_sigint_stops_a_long_analysis(dent_pair, tmp_path):
    ref, exa, _ = dent_pair
    out = tmp_path / "atlas"
    proc = subprocess.Popen([sys.executable, "-c", SCRIPT, str(ref), str(exa), str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=os.environ.copy())
    assert proc.stdout.readline().strip() == "ready"
    time.sleep(1.5)  # well inside the fit or the sweep (the whole run takes minutes)
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=60)
    stopped_after = time.monotonic() - sent
    assert proc.returncode == 42, (stdout, stderr)
    assert "interrupted after" in stdout
    # note: glint polls between views and ICP iterations; 10 s is far above one view at 384 px.
    assert stopped_after < 10
    # Nothing half-written: no atlas folder, no staging folder beside it.
    assert not out.exists()
    assert [p.name for p in pathlib.Path(tmp_path).iterdir()] == []
