#!/usr/bin/env python3
"""Opens a glint report.html in headless Chromium over the DevTools protocol and checks it.

  report_html_check.py CHROMIUM ATLAS_DIR WORKDIR [--words-only]

ATLAS_DIR holds report.html, report.json, regions.csv and atlas.ply of one sweep. The page is
loaded from disk (file://…/report.html#selftest); its self-test writes a JSON verdict into
#selftest-verdict. Fails (exit 1, reasons listed) when
  - the verdict is not ok (canvas not drawn, wrong colour at the known vertex, picking,
    the click on region row 1 did not fly the camera to the region's centroid);
  - any console error, uncaught exception or error log entry appeared;
  - the page asked for anything over the network, or the HTML names an external resource;
  - the screenshot's 3D view is blank;
  - the known vertex's value differs from atlas.ply's shape change (`scalar_shape_change_<unit>`), or its expected colour from
    the diverging map computed here (ColorBrewer RdBu, 9 classes, reversed);
  - the region table does not list report.json's regions;
  - the banner's verdict is not the sentence report.json's zoom 0 makes ("2 regions: 1 dent,
    1 bump"), or its warnings are not report.json's (the run's, then the renderer's), each with a
    severity;
  - atlas.png is not shown inline at its width, or a region lacks its label, its finding
    sentence (first under its row), its place and depth +- as report.json has them, its
    evidence sentence (folded under "details") or its best view's name;
  - the fit table lacks the mode, or (for a fit made here) the rotation in °, the translation
    and its length in the unit, the RMS in the unit, the iterations, as report.json holds them;
  - the self-test found a region without an outline, a label not dimmed from behind, or a pick
    marker whose size on screen changed when the camera moved twice as far.
With --words-only the page is opened without its self-test and only the words are checked.
WebGL runs on SwiftShader (--use-angle=swiftshader --enable-unsafe-swiftshader): no GPU needed.
"""
import base64
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import urllib.request
import zlib

import websocket

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from viewers_check import read_ply  # noqa: E402  (the atlas.ply reader the viewer tests use)

RDBU = [(33, 102, 172), (67, 147, 195), (146, 197, 222), (209, 229, 240), (247, 247, 247),
        (253, 219, 199), (244, 165, 130), (214, 96, 77), (178, 24, 43)]
TIMEOUT_S = 120


class DevTools:
    """A minimal Chrome DevTools protocol client: commands by id, events kept in order."""

    def __init__(self, url):
        self.ws = websocket.create_connection(url, timeout=TIMEOUT_S, suppress_origin=True)
        self.next_id = 0
        self.events = []

    def call(self, method, **params):
        self.next_id += 1
        my_id = self.next_id
        self.ws.send(json.dumps({"id": my_id, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == my_id:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            if "method" in msg:
                self.events.append(msg)

    def evaluate(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"evaluate {expression!r}: {r['exceptionDetails']}")
        return r["result"].get("value")


def start_chromium(chromium, profile):
    args = [chromium, "--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            "--no-first-run", "--no-default-browser-check", "--remote-allow-origins=*",
            "--window-size=1400,1100", f"--user-data-dir={profile}", "--remote-debugging-port=0", "about:blank"]
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
    page = next(t for t in targets if t.get("type") == "page")
    return proc, page["webSocketDebuggerUrl"]


def decode_png(data):
    """RGB(A) 8-bit non-interlaced PNG → (width, height, channels, bytearray of rows)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            assert depth == 8 and colour in (2, 6) and interlace == 0, "unexpected PNG format"
            ch = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    raw, stride = zlib.decompress(idat), w * ch
    out, prev = bytearray(), bytearray(stride)
    for y in range(h):
        f, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = row[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            if f == 1: row[i] = (row[i] + a) & 255
            elif f == 2: row[i] = (row[i] + b) & 255
            elif f == 3: row[i] = (row[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += row
        prev = row
    return w, h, ch, out


def rdbu(t):
    t = min(1.0, max(0.0, t))
    x = t * (len(RDBU) - 1)
    i = min(len(RDBU) - 2, int(x))
    f = x - i
    return [RDBU[i][c] * (1 - f) + RDBU[i + 1][c] * f for c in range(3)]


def console_problems(events):
    problems = []
    for e in events:
        m, p = e["method"], e.get("params", {})
        if m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            problems.append("console." + p["type"] + ": " + " ".join(str(a.get("value", a.get("description")))
                                                                     for a in p.get("args", [])))
        elif m == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            problems.append("exception: " + str(d.get("exception", {}).get("description", d.get("text"))))
        elif m == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            problems.append("log: " + p["entry"].get("text", ""))
        elif m == "Network.requestWillBeSent":
            url = p.get("request", {}).get("url", "")
            if not re.match(r"^(file|data|blob|about|chrome|devtools):", url):
                problems.append("network request: " + url[:200])
    return problems


def check_screenshot(shot, rect, workdir):
    with open(os.path.join(workdir, "report_screenshot.png"), "wb") as f:
        f.write(shot)
    w, h, ch, px = decode_png(shot)
    x0, y0 = int(rect["x"]), int(rect["y"])
    x1, y1 = min(w, int(rect["x"] + rect["width"])), min(h, int(rect["y"] + rect["height"]))
    bg = (0x2a, 0x2e, 0x36)
    drawn, colours, total = 0, set(), 0
    for y in range(y0, y1, 2):
        for x in range(x0, x1, 2):
            o = (y * w + x) * ch
            c = tuple(px[o:o + 3])
            total += 1
            colours.add(c)
            if max(abs(c[i] - bg[i]) for i in range(3)) > 8:
                drawn += 1
    frac = drawn / max(1, total)
    print(f"screenshot {w}x{h}: 3D view {x1 - x0}x{y1 - y0} px, {100 * frac:.1f} % drawn, {len(colours)} colours")
    return [] if frac > 0.02 and len(colours) > 50 else [f"3D view looks blank: {100 * frac:.2f} % drawn, "
                                                         f"{len(colours)} colours"]


def check_verdict(verdict, atlas_dir):
    problems = [] if verdict.get("ok") else ["self-test verdict not ok"]
    colour = verdict["checks"].get("colour", {})
    field = colour.get("field", "")
    if field.startswith("shape_change_"):
        # The page's field has the atlas's name; the PLY writes it as CloudCompare names it.
        values = read_ply(os.path.join(atlas_dir, "atlas.ply"))["scalar_" + field]
        v, value = colour["vertex"], colour["value"]
        if abs(values[v] - value) > 1e-6 * max(1.0, abs(value)):
            problems.append(f"vertex {v}: page value {value}, atlas.ply {field} {values[v]}")
        low, high = colour["low"], colour["high"]
        if not (high > 0 and abs(low + high) <= 1e-9 * high):
            problems.append(f"distance range [{low}, {high}] is not symmetric about 0")
        expected = rdbu((value - low) / (high - low))
        if max(abs(a - b) for a, b in zip(expected, colour["vertex_colour"])) > 1.5:
            problems.append(f"page's colour of vertex {v} {colour['vertex_colour']} differs from RdBu {expected}")
        if abs(value) < 0.2 * high:
            problems.append(f"the known vertex's value {value} is too pale to test the colour map")
    else:
        problems.append(f"the colour check used {field!r}, not the signed shape change")
    return problems


def plural(n, word):
    if word == "surface gone":
        return f"{n} surface gone" if n == 1 else f"{n} surfaces gone"
    return f"{n} {word}" + ("" if n == 1 else "s")


def kind_of(region):
    return "surface gone" if region.get("surface_gone") else region["kind"]


def expected_verdict(zoom):
    """The banner's sentence for report.json's zoom 0, made here from the numbers."""
    regions = zoom["regions"]
    if regions:
        kinds = list(dict.fromkeys(kind_of(r) for r in regions))
        return plural(len(regions), "region") + ": " + ", ".join(
            plural(sum(kind_of(r) == k for r in regions), k) for k in kinds)
    if any("no regions are reported" in w for w in zoom.get("warnings", [])):
        return "no regions: no quiet scale, see warnings"
    return "no damage found above the floors"


PAGE_WORDS = """(() => {
  const rows = (sel) => [...document.querySelectorAll(sel)];
  const atlas = document.getElementById('atlas-picture');
  const fit = document.getElementById('fit-table');
  return {
    verdict: document.getElementById('verdict').textContent,
    warnings: rows('#warnings li').map((li) => ({ text: li.textContent, severity: li.className })),
    atlas: { complete: atlas.complete, natural_width: atlas.naturalWidth, src: atlas.src.slice(0, 22) },
    fit: fit ? Object.fromEntries(rows('#fit-table tr').map((tr) => [tr.cells[0].textContent, tr.cells[1].textContent])) : null,
    labels: rows('#region-labels .region-label').map((d) => d.getAttribute('data-region')),
    evidence: rows('#regions tr.evidence').map((tr) => ({ id: tr.getAttribute('data-evidence'), text: tr.textContent })),
    cells: rows('#regions tr.region').map((tr) => [...tr.cells].map((td) => td.textContent)),
  };
})()"""


def page_number(text):
    return float(text.replace("\u2212", "-"))


def check_fit_words(fit, report):
    """The fit table: rotation in °, translation as a vector and a length in the unit, RMS in the
    unit, the mode and the iterations, each the number report.json holds."""
    unit, f, problems = report["unit"] or "units", report["fit"], []
    mode = report["analysis"]["registration"]["mode"]
    if not fit or not fit.get("mode", "").startswith({"file": "given", "truth": "given"}.get(mode, mode)):
        return [f"fit table {fit} does not name the mode {mode!r}"]
    if "translation" not in f:
        return problems
    m = re.fullmatch(rf"\((.+)\) {re.escape(unit)}, length (\S+) {re.escape(unit)}", fit.get("translation", ""))
    length = math.hypot(*f["translation"])
    if not m or abs(page_number(m.group(2)) - length) > 5e-3 * max(length, 1e-9) + 1e-12:
        problems.append(f"fit translation {fit.get('translation')!r}, report.json {f['translation']} {unit}")
    m = re.fullmatch(rf"(\S+) {re.escape(unit)}", fit.get("RMS distance", ""))
    if not m or abs(page_number(m.group(1)) - f["rms"]) > 5e-3 * f["rms"] + 1e-12:
        problems.append(f"fit RMS {fit.get('RMS distance')!r}, report.json {f['rms']} {unit}")
    m = re.match(r"(\S+) ° about \(", fit.get("rotation", ""))
    if not m or abs(page_number(m.group(1)) - f["rotation_deg"]) > 5e-3 * abs(f["rotation_deg"]) + 1e-9:
        problems.append(f"fit rotation {fit.get('rotation')!r}, report.json {f['rotation_deg']}°")
    if fit.get("iterations") != str(f["iterations"]):
        problems.append(f"fit iterations {fit.get('iterations')!r}, report.json {f['iterations']}")
    return problems


def check_page_words(words, report, atlas_dir):
    """The banner, atlas.png, the fit, the regions' labels and evidence against report.json."""
    problems = []
    z0 = report["zooms"][0]
    if words["verdict"] != expected_verdict(z0):
        problems.append(f"banner says {words['verdict']!r}, report.json makes it {expected_verdict(z0)!r}")
    warnings = report["warnings"] + ["renderer: " + w for w in report["device"]["warnings"]]
    if [w["text"] for w in words["warnings"]] != warnings:
        problems.append(f"banner warnings {words['warnings']}, report.json {warnings}")
    if any(w["severity"] not in ("severe", "caution", "info") for w in words["warnings"]):
        problems.append(f"a banner warning without a severity: {words['warnings']}")
    with open(os.path.join(atlas_dir, "atlas.png"), "rb") as f:
        width = struct.unpack(">I", f.read(24)[16:20])[0]
    a = words["atlas"]
    if not (a["complete"] and a["natural_width"] == width and a["src"] == "data:image/png;base64,"):
        problems.append(f"atlas picture {a}, atlas.png is {width} px wide")
    problems += check_fit_words(words["fit"], report) if report["fit"] else []
    ids = [str(r["id"]) for r in z0["regions"]]
    if words["labels"] != ids:
        problems.append(f"region labels {words['labels']}, report.json regions {ids}")
    # A region without a depth or volume (missing surface: null in report.json) shows "—".
    for r, cells in zip(z0["regions"], words["cells"]):
        for value, cell, name in ((r["peak_depth"], cells[2], "peak depth"), (r["volume"], cells[5], "volume")):
            if (value is None) != (cell == "—") or (value is not None and abs(page_number(cell) - value) >
                                                      5e-3 * abs(value) + 1e-9):
                problems.append(f"region {r['id']}: {name} cell {cell!r}, report.json {value}")
    # The plain words in the table (issue 51): the place and the depth's +- as report.json has them.
    for r, cells in zip(z0["regions"], words["cells"]):
        if cells[6] != r.get("place", "—"):
            problems.append(f"region {r['id']}: place cell {cells[6]!r}, report.json {r.get('place')!r}")
        u = r.get("depth_uncertainty")
        if r.get("surface_gone") or r["peak_depth"] is None or u is None:
            if cells[3] != "\u2014":
                problems.append(f"region {r['id']}: +- cell {cells[3]!r} where no depth is measured between surfaces")
        elif abs(page_number(cells[3]) - u) > 5e-3 * u + 1e-9:
            problems.append(f"region {r['id']}: +- cell {cells[3]!r}, report.json depth_uncertainty {u}")
    # The row under it: the finding's sentence first, the best view, then (folded) the evidence.
    evidence = {e["id"]: e["text"] for e in words["evidence"]}
    for r in z0["regions"]:
        view = f"z0_az{r['best_view_azimuth_deg']:05.1f}_el{r['best_view_elevation_deg']:+05.1f}"
        text = evidence.get(str(r["id"]), "")
        if r["evidence"] not in text or f"best view {view}" not in text:
            problems.append(f"region {r['id']}: evidence row {text!r} lacks {r['evidence']!r} or view {view}")
        if "finding" in r and not text.startswith(r["finding"]):
            problems.append(f"region {r['id']}: the row under it does not open with its finding {r['finding']!r}: {text!r}")
    return problems


def check_overlays(verdict, report):
    """Every region has an outline and a label; the marker scaled with the camera's distance."""
    o, problems = verdict["checks"].get("overlays", {}), []
    ids = [r["id"] for r in report["zooms"][0]["regions"]]
    if [r["id"] for r in o.get("regions", [])] != ids or not all(r["segments"] >= 3 and r["label"] for r in o["regions"]):
        problems.append(f"outlines and labels {o.get('regions')}, regions {ids}")
    m = o.get("marker", {})
    if ids and not (m.get("ok") and abs(m["ratio"] - 2) < 0.05):
        problems.append(f"pick marker did not keep its size on screen: {m}")
    if ids and not o.get("occlusion", {}).get("ok"):
        problems.append(f"region label not dimmed behind the surface: {o.get('occlusion')}")
    return problems


def load_page_words(dt, html_path):
    """Without the self-test: the page's words once it has built them."""
    dt.call("Page.navigate", url="file://" + html_path)
    deadline = time.time() + TIMEOUT_S
    while time.time() < deadline:
        time.sleep(0.5)
        if dt.evaluate("(document.getElementById('verdict') || {}).textContent || ''") and \
                dt.evaluate("document.getElementById('atlas-picture').complete"):
            return dt.evaluate(PAGE_WORDS)
    raise SystemExit("FAIL: the page wrote no verdict within %d s" % TIMEOUT_S)


def main():
    chromium, atlas_dir, workdir = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
    words_only = "--words-only" in sys.argv[4:]
    html_path = os.path.join(atlas_dir, "report.html")
    with open(html_path, encoding="utf-8") as f:
        html = f.read()
    problems = []
    markup = re.sub(r"(<script\b[^>]*>).*?</script>", r"\1</script>", html, flags=re.S | re.I)
    if re.search(r"<(script|link|img|iframe|source)\b[^>]*\s(src|href)\s*=", markup, re.I):
        problems.append("report.html names an external resource")
    print(f"report.html: {len(html.encode()) / 1e6:.2f} MB")
    profile = tempfile.mkdtemp(prefix="glint-chromium-")
    proc = None
    try:
        proc, ws_url = start_chromium(chromium, profile)
        dt = DevTools(ws_url)
        for domain in ("Runtime", "Log", "Page", "Network"):
            dt.call(domain + ".enable")
        with open(os.path.join(atlas_dir, "report.json")) as f:
            report = json.load(f)
        if words_only:
            words = load_page_words(dt, html_path)
            print("page:", json.dumps(words, indent=1, ensure_ascii=False))
            problems += check_page_words(words, report, atlas_dir)
            dt.call("Runtime.evaluate", expression="0")
            problems += console_problems(dt.events)
            return finish(problems)
        dt.call("Page.navigate", url="file://" + html_path + "#selftest")
        deadline, text = time.time() + TIMEOUT_S, ""
        while not text and time.time() < deadline:
            time.sleep(0.5)
            text = dt.evaluate("(document.getElementById('selftest-verdict') || {}).textContent || ''")
        if not text:
            raise SystemExit("FAIL: the page wrote no self-test verdict within %d s" % TIMEOUT_S)
        verdict = json.loads(text)
        print("verdict:", json.dumps(verdict, indent=1))
        problems += check_verdict(verdict, atlas_dir)
        problems += check_overlays(verdict, report)
        problems += check_page_words(dt.evaluate(PAGE_WORDS), report, atlas_dir)
        rows = dt.evaluate("document.querySelectorAll('#regions tbody tr[data-region]').length")
        if rows != len(report["zooms"][0]["regions"]) or rows == 0:
            problems.append(f"region table has {rows} rows, report.json {len(report['zooms'][0]['regions'])} regions")
        rect = dt.evaluate("(() => { const r = document.getElementById('view3d').getBoundingClientRect();"
                           " return {x: r.x, y: r.y, width: r.width, height: r.height}; })()")
        shot = base64.b64decode(dt.call("Page.captureScreenshot", format="png")["data"])
        problems += check_screenshot(shot, rect, workdir)
        dt.call("Runtime.evaluate", expression="0")  # flush events still queued
        problems += console_problems(dt.events)
    finally:
        if proc:
            proc.kill()
            proc.wait()
        shutil.rmtree(profile, ignore_errors=True)
    return finish(problems)


def finish(problems):
    if problems:
        print("FAIL:\n  " + "\n  ".join(problems))
        return 1
    print("ok: report.html passes its checks in headless Chromium")
    return 0


if __name__ == "__main__":
    sys.exit(main())
