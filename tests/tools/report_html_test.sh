#!/usr/bin/env bash
# report.html in a real browser: headless Chromium (Debian's chromium) opens the page glint
# wrote from disk with "#selftest", the page checks itself (WebGL canvas drawn, the colour at a
# known vertex, picking, a click on region row 1 flies the camera there) and
# report_html_check.py also fails on any console error, exception or network request, checks
# the screenshot is not blank and the vertex's value against atlas.ply, and the banner, atlas.png,
# region outlines, labels and evidence, the pick marker and the fit table against report.json
# (a second, registered pair for the fit's translation and RMS). Chromium or Python's
# websocket module (python3-websocket) missing: skipped (exit 77) with the reason.
#   report_html_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/report_html
here=$(cd "$(dirname "$0")" && pwd)
skip() { echo "SKIP: $*"; exit 77; }

chromium=""
for c in chromium chromium-browser google-chrome; do
    if command -v "$c" >/dev/null; then chromium=$(command -v "$c"); break; fi
done
[ -n "$chromium" ] || skip "no chromium (Debian package chromium)"
# A Python that has the websocket client: the system one (python3-websocket), also when
# another python3 is first on PATH.
python=""
for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c "import websocket" 2>/dev/null; then python=$p; break; fi
done
[ -n "$python" ] || skip "python3 cannot import websocket (Debian package python3-websocket)"

rm -rf "$work"
mkdir -p "$work"
"$glint" --quiet phantom sphere --size 10 --scheme ico --resolution 4 -o "$work/ref.ply"
"$glint" --quiet phantom sphere --size 10 --scheme ico --resolution 4 \
    --damage "dent:center=10,0,0 radius=3 depth=0.6" --damage "bump:center=0,0,10 radius=3 depth=0.4" \
    -o "$work/exa.ply"
"$glint" --quiet sweep "$work/ref.ply" "$work/exa.ply" --unit mm --size 96 --azimuth-step 45 --elevations -30,30 \
    --no-exr -o "$work/atlas"
[ -s "$work/atlas/report.html" ] || { echo "FAIL: no report.html"; exit 1; }
"$python" "$here/report_html_check.py" "$chromium" "$work/atlas" "$work"
# A registered pair (the condyle: no symmetry to slide along): the page's fit table, banner and
# region words against its report.json, without the self-test.
"$glint" --quiet phantom condyle --scheme ico --resolution 4 -o "$work/condyle_ref.ply"
"$glint" --quiet phantom condyle --scheme uv --resolution 40 --damage "dent:center=2,-1,8.8 radius=3 depth=0.6" \
    --pose "4,-3,5,0.3,-0.2,0.1" -o "$work/condyle_exa.ply"
"$glint" --quiet sweep "$work/condyle_ref.ply" "$work/condyle_exa.ply" --register --unit mm --size 64 \
    --azimuth-step 60 --elevations -45,0,45 --no-exr -o "$work/registered"
"$python" "$here/report_html_check.py" "$chromium" "$work/registered" "$work" --words-only
