#!/usr/bin/env python3
"""The live view of report.html against glint's own numbers, in headless Chromium.

  report_live_check.py CHROMIUM WORKDIR DENT_ATLAS RETESSELLATED_ATLAS

DENT_ATLAS: a sweep of a sphere and the same sphere with a dent, three zooms from fine to one
whose pixel is wider than the dent, every view's numbers as EXR (`glint sweep --exr`). RETESSELLATED_ATLAS:
a sweep of an undamaged sphere against the same sphere tessellated otherwise. Each page is
loaded from disk (file://…/report.html#selftest) and fails (exit 1, reasons listed) when
  - its self-test verdict is not ok, or its live view did not start (report.js, live.js);
  - the angle the page computes for a sweep view, rendered again in the browser at the
    view's azimuth, elevation, footprint, size and averaging (glintLive.measure), differs from
    the view's EXR (angle_deg, read with oiiotool) by 1° or more at the dent's strongest pixel
    or at more than 2 % of the dent's pixels (those where glint measured ≥ 1°); the paper's
    |RGB| difference (the sweep's metric there) by more than 8-bit rounding, or the signed
    depth by more than 1e-4 mm;
  - zooming out past the dent does not make it fade: the largest angle of the view facing the
    dent must fall from zoom to zoom, and at the coarsest be below a third of the finest's, in
    glint's EXRs and in the page alike;
  - on the undamaged re-tessellated pair, the page's angles are not ~0 (99th percentile ≥ 0.2°
    or largest ≥ 1° in any view) or their mean differs from glint's per-view mean (report.json
    views[].mean_angle_deg) by 0.02° or more;
  - with WebGL2 switched off (--disable-webgl2), the page does not say so in the live view or
    its atlas view fails its self-test;
  - any console error, exception or network request.
It prints the measured numbers and the live view's frames per second on this machine (not
asserted: speed is bench's). WORKDIR gets live_screenshot.png (the live view at the dent's
region's best view).
"""
import base64
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_html_check import DevTools, TIMEOUT_S, check_screenshot, console_problems  # noqa: E402

import urllib.request  # noqa: E402


def start(chromium, profile, extra):
    args = [chromium, "--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            "--no-first-run", "--no-default-browser-check", "--remote-allow-origins=*",
            "--window-size=1400,1100", f"--user-data-dir={profile}", "--remote-debugging-port=0"] + extra + ["about:blank"]
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    port_file = os.path.join(profile, "DevToolsActivePort")
    deadline = time.time() + 60
    while not os.path.exists(port_file) or os.path.getsize(port_file) == 0:
        if proc.poll() is not None or time.time() > deadline:
            proc.kill()
            raise SystemExit("FAIL: chromium did not start: " + proc.stderr.read().decode(errors="replace")[-2000:])
        time.sleep(0.1)
    with open(port_file) as f:
        port = int(f.readline())
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=30) as r:
        targets = json.load(r)
    return proc, next(t for t in targets if t.get("type") == "page")["webSocketDebuggerUrl"]


class Page:
    """One report.html opened in its own headless Chromium, its self-test run."""

    def __init__(self, chromium, atlas_dir, extra=()):
        self.profile = tempfile.mkdtemp(prefix="glint-chromium-")
        self.proc, url = start(chromium, self.profile, list(extra))
        self.dt = DevTools(url)
        for domain in ("Runtime", "Log", "Page", "Network"):
            self.dt.call(domain + ".enable")
        self.dt.call("Page.navigate", url="file://" + os.path.join(atlas_dir, "report.html") + "#selftest")
        deadline, text = time.time() + TIMEOUT_S, ""
        while not text and time.time() < deadline:
            time.sleep(0.5)
            text = self.dt.evaluate("(document.getElementById('selftest-verdict') || {}).textContent || ''")
        if not text:
            raise SystemExit("FAIL: the page wrote no self-test verdict within %d s" % TIMEOUT_S)
        self.verdict = json.loads(text)

    def close(self):
        self.dt.call("Runtime.evaluate", expression="0")  # flush events still queued
        problems = console_problems(self.dt.events)
        self.proc.kill()
        self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)
        return problems


def exr_channel(path, channel):
    """One channel of an EXR as rows top first (NaN where glint compared nothing)."""
    out = subprocess.run(["oiiotool", "--info", "-v", "--dumpdata", path], check=True, capture_output=True,
                         text=True).stdout
    names = re.search(r"channel list:\s*(.*)", out).group(1).split(", ")
    k = names.index(channel)
    values = {}
    width = height = 0
    for line in out.splitlines():
        m = re.match(r"\s*Pixel \((\d+), (\d+)\):\s*(.*)", line)
        if m:
            x, y = int(m.group(1)), int(m.group(2))
            values[(x, y)] = float(m.group(3).split()[k])
            width, height = max(width, x + 1), max(height, y + 1)
    return width, height, [values[(x, y)] for y in range(height) for x in range(width)]


def view_of(report, zoom, azimuth, elevation):
    return next(v for v in report["views"]
                if v["zoom"] == zoom and abs(v["azimuth_deg"] - azimuth) < 1e-6 and abs(v["elevation_deg"] - elevation) < 1e-6)


def measure(page, report, view):
    zoom = report["zooms"][view["zoom"]]
    spec = {"azimuth": view["azimuth_deg"], "elevation": view["elevation_deg"], "footprint": zoom["footprint"],
            "width": zoom["image_size"], "height": zoom["image_size"],
            "supersample": report["analysis"]["sweep"]["supersample"]}
    return page.dt.evaluate("glintLive.measure(%s)" % json.dumps(spec))


def stem(view):
    return "z%d_az%05.1f_el%+05.1f" % (view["zoom"], view["azimuth_deg"], view["elevation_deg"])


def compare_other_metrics(name, live, exr_path, both, problems):
    """The page's |RGB| difference and signed depth against the EXR's, where both compared."""
    _, _, rgb = exr_channel(exr_path, "rgb_rgb")
    _, _, depth = exr_channel(exr_path, "signed_depth")
    # note: 8-bit rounding of 0.5·n + 0.5 from float normals resolved in two orders: a channel
    # on a rounding edge may move by 1 of 255 on one side, the mean of three by 1/3.
    rgb_off = [i for i in both if abs(live["rgb"][i] - rgb[i]) > 0.34]
    # note: 1e-4 mm: float depths of a 20 mm scene differ by a few 1e-6 mm.
    depth_diffs = [abs(live["depth"][i] - depth[i]) for i in both]
    print(f"{name}: |RGB| difference: {len(rgb_off)} of {len(both)} pixels off by more than 1/3 "
          f"(largest glint {max(rgb[i] for i in both):.2f}, page {max(live['rgb'][i] for i in both):.2f}); "
          f"signed depth: largest |page − glint| {max(depth_diffs):.2e} mm "
          f"(deepest glint {min(depth[i] for i in both):.4f} mm, page {min(live['depth'][i] for i in both):.4f} mm)")
    if len(rgb_off) > 0.001 * len(both):
        problems.append(f"{name}: |RGB| difference off by more than 1/3 at {len(rgb_off)} of {len(both)} pixels")
    if max(depth_diffs) > 1e-4:
        problems.append(f"{name}: signed depth differs from glint's by up to {max(depth_diffs):.2e} mm")


def compare_with_exr(name, live, exr_path, problems):
    """The page's angles (and the other metrics) against the view's EXR, pixel by pixel.
    Returns both largest angles."""
    w, h, glint = exr_channel(exr_path, "angle_deg")
    if (w, h) != (live["width"], live["height"]):
        problems.append(f"{name}: EXR {w}x{h}, page {live['width']}x{live['height']}")
        return 0.0, 0.0
    page = live["angle"]
    both = [i for i in range(w * h) if glint[i] == glint[i] and page[i] is not None]
    only = sum(1 for i in range(w * h) if (glint[i] == glint[i]) != (page[i] is not None))
    dent = [i for i in both if glint[i] >= 1.0]
    worst = max(both, key=lambda i: glint[i]) if both else None
    off = [i for i in dent if abs(page[i] - glint[i]) >= 1.0]
    diffs = sorted(abs(page[i] - glint[i]) for i in both)
    glint_max = max((glint[i] for i in both), default=0.0)
    page_max = max((page[i] for i in both), default=0.0)
    print(f"{name}: {len(both)} pixels compared by both, {only} by one only; dent pixels (glint ≥ 1°) {len(dent)}; "
          f"strongest pixel {worst % w if worst is not None else '-'},{worst // w if worst is not None else '-'}: "
          f"glint {glint[worst] if worst is not None else 0:.3f}°, page {page[worst] if worst is not None else 0:.3f}°; "
          f"|page − glint| median {diffs[len(diffs) // 2] if diffs else 0:.4f}°, max {diffs[-1] if diffs else 0:.4f}°; "
          f"{len(off)} dent pixels off by ≥ 1°; largest glint {glint_max:.3f}°, page {page_max:.3f}°")
    if worst is None:
        problems.append(f"{name}: no pixel compared by both")
        return glint_max, page_max
    if abs(page[worst] - glint[worst]) >= 1.0:
        problems.append(f"{name}: at glint's strongest pixel the page shows {page[worst]:.3f}°, glint {glint[worst]:.3f}°")
    if len(off) > 0.02 * max(1, len(dent)):
        problems.append(f"{name}: {len(off)} of {len(dent)} dent pixels differ from glint by ≥ 1°")
    if only > 0.01 * max(1, len(both)):
        problems.append(f"{name}: {only} pixels compared by one side only ({len(both)} by both)")
    compare_other_metrics(name, live, exr_path, both, problems)
    return glint_max, page_max


def check_verdict(name, verdict, expect_live, problems, whole=True):
    """The page's self-test: whole, or (whole=False: a page with no region, where the atlas
    check finds no close-up to test colours on) its live part and no error."""
    live = verdict.get("checks", {}).get("live", {})
    print(f"{name}: self-test {'ok' if verdict.get('ok') else 'NOT ok'}; live: {json.dumps(live)}")
    if (not verdict.get("ok") if whole else not live.get("ok") or verdict.get("errors")):
        problems.append(f"{name}: self-test verdict not ok: {json.dumps(verdict)[:3000]}")
    if bool(live.get("available")) != expect_live:
        problems.append(f"{name}: live view available = {live.get('available')}, expected {expect_live}")


def dent_page(chromium, workdir, atlas, problems):
    with open(os.path.join(atlas, "report.json")) as f:
        report = json.load(f)
    page = Page(chromium, atlas)
    try:
        check_verdict("dent", page.verdict, True, problems)
        maxima = []
        for zoom in range(len(report["zooms"])):
            view = view_of(report, zoom, 0.0, 0.0)
            live = measure(page, report, view)
            maxima.append(compare_with_exr(f"dent, zoom {zoom} ({report['zooms'][zoom]['footprint']} mm/px, "
                                           f"{live['width']}² px, s = {live['supersample']})", live,
                                           os.path.join(atlas, "views", stem(view) + ".exr"), problems))
        glint_maxima, page_maxima = [g for g, _ in maxima], [p for _, p in maxima]
        print("fade: largest angle facing the dent, zoom by zoom: glint " +
              " → ".join(f"{g:.3f}°" for g in glint_maxima) + ", page " + " → ".join(f"{p:.3f}°" for p in page_maxima))
        for name, m in (("glint", glint_maxima), ("page", page_maxima)):
            if len(m) < 2 or any(b >= a for a, b in zip(m, m[1:])) or not m[-1] < m[0] / 3:
                problems.append(f"the dent does not fade as the zoom coarsens ({name}): " + " → ".join(f"{x:.3f}°" for x in m))
        # The live view as a reader sees it, at the dent region's best view.
        page.dt.evaluate("document.getElementById('mode-live').click()")
        page.dt.evaluate("(() => { const r = glintLive; const v = %d; r.jumpToView(v); })()"
                         % report["zooms"][0]["regions"][0]["best_view"])
        time.sleep(1.5)
        rect = page.dt.evaluate("(() => { const r = document.getElementById('live-viewer').getBoundingClientRect();"
                                " return {x: r.x, y: r.y, width: r.width, height: r.height}; })()")
        shot = base64.b64decode(page.dt.call("Page.captureScreenshot", format="png")["data"])
        problems += check_screenshot(shot, rect, workdir)
        os.replace(os.path.join(workdir, "report_screenshot.png"), os.path.join(workdir, "live_screenshot.png"))
        fps = page.dt.evaluate("glintLive.bench({width: 512, height: 512, frames: 5})")
        print(f"live view speed here (SwiftShader, not asserted): {fps['fps']:.2f} fps at {fps['width']}² "
              f"with s = {fps['supersample']}, {fps['triangles'][0]} + {fps['triangles'][1]} triangles")
    finally:
        problems += ["dent page: " + p for p in page.close()]


def retessellated_page(chromium, atlas, problems):
    with open(os.path.join(atlas, "report.json")) as f:
        report = json.load(f)
    page = Page(chromium, atlas)
    try:
        check_verdict("re-tessellated", page.verdict, True, problems, whole=False)
        for view in report["views"]:
            live = measure(page, report, view)
            angles = sorted(a for a in live["angle"] if a is not None)
            if not angles:
                problems.append(f"re-tessellated view {view['index']}: no pixel compared")
                continue
            mean = sum(angles) / len(angles)
            p99, top = angles[int(0.99 * (len(angles) - 1))], angles[-1]
            print(f"re-tessellated view {view['index']} (az {view['azimuth_deg']}, el {view['elevation_deg']}): "
                  f"{len(angles)} pixels, page mean {mean:.4f}° p99 {p99:.4f}° max {top:.4f}°; "
                  f"glint mean {view['mean_angle_deg']:.4f}° max {view['max_angle_deg']:.4f}° over {view['compared']} pixels")
            if p99 >= 0.2 or top >= 1.0:
                problems.append(f"re-tessellated view {view['index']}: not ~0: p99 {p99:.3f}°, max {top:.3f}°")
            # note: 0.02° is glint's own floor near 0°: its acos of float normals returns 0 or
            # ≥ 0.02° (scanner/compare.cpp), the page's atan2 the small angles themselves, so
            # glint's means run ~0.01° lower on a pair this close.
            if abs(mean - view["mean_angle_deg"]) >= 0.02:
                problems.append(f"re-tessellated view {view['index']}: page mean {mean:.4f}°, glint {view['mean_angle_deg']:.4f}°")
    finally:
        problems += ["re-tessellated page: " + p for p in page.close()]


def fallback_page(chromium, atlas, problems):
    page = Page(chromium, atlas, ["--disable-webgl2"])
    try:
        check_verdict("without WebGL2", page.verdict, False, problems)
        message = page.verdict.get("checks", {}).get("live", {}).get("message", "")
        if "WebGL2" not in message:
            problems.append(f"without WebGL2 the live view says {message!r}")
    finally:
        problems += ["page without WebGL2: " + p for p in page.close()]


def main():
    chromium, workdir, dent_atlas, retessellated_atlas = sys.argv[1], sys.argv[2], *map(os.path.abspath, sys.argv[3:5])
    problems = []
    dent_page(chromium, workdir, dent_atlas, problems)
    retessellated_page(chromium, retessellated_atlas, problems)
    fallback_page(chromium, dent_atlas, problems)
    if problems:
        print("FAIL:\n  " + "\n  ".join(problems))
        return 1
    print("ok: report.html's live view renders, agrees with glint's per-view angles, shows ~0 on a "
          "re-tessellated pair, fades the dent when zoomed out, and says so without WebGL2")
    return 0


if __name__ == "__main__":
    sys.exit(main())
