#!/usr/bin/env python3
"""Opens a glint report.html in headless Chromium over the DevTools protocol and checks it.

  report_html_check.py CHROMIUM ATLAS_DIR WORKDIR

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
  - the region table does not list report.json's regions.
WebGL runs on SwiftShader (--use-angle=swiftshader --enable-unsafe-swiftshader): no GPU needed.
"""
import base64
import json
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


def main():
    chromium, atlas_dir, workdir = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
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
        with open(os.path.join(atlas_dir, "report.json")) as f:
            report = json.load(f)
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
    if problems:
        print("FAIL:\n  " + "\n  ".join(problems))
        return 1
    print("ok: report.html passes its self-test in headless Chromium")
    return 0


if __name__ == "__main__":
    sys.exit(main())
