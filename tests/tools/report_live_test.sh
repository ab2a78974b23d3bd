#!/usr/bin/env bash
# report.html's live view in a real browser (issue 28): headless Chromium (WebGL2 on
# SwiftShader) opens the pages of two sweeps and report_live_check.py compares what the page
# computes with glint's own per-view numbers:
#   - a sphere (radius 10 mm) and the same sphere with a 0.3 mm dent of 1.5 mm radius, three
#     zooms (0.1, 1 and 4 mm/px: the last wider than the dent), s = 8, per-view EXRs: the
#     page's angle, |RGB| difference (the paper's metric, the sweep's here) and signed depth per
#     pixel against the EXR's, and the dent fading as the zoom coarsens, in both;
#   - an undamaged sphere against the same sphere tessellated otherwise (icosphere against a
#     latitude/longitude grid): the page's angles ~0 and their mean glint's;
#   - the first page again with WebGL2 switched off: the live view says so, the atlas works.
# Chromium, Python's websocket module (python3-websocket) or oiiotool (openimageio-tools)
# missing: skipped (exit 77) with the reason.
#   report_live_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/report_live
here=$(cd "$(dirname "$0")" && pwd)
skip() { echo "SKIP: $*"; exit 77; }

chromium=""
for c in chromium chromium-browser google-chrome; do
    if command -v "$c" >/dev/null; then chromium=$(command -v "$c"); break; fi
done
[ -n "$chromium" ] || skip "no chromium (Debian package chromium)"
python=""
for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c "import websocket" 2>/dev/null; then python=$p; break; fi
done
[ -n "$python" ] || skip "python3 cannot import websocket (Debian package python3-websocket)"
command -v oiiotool >/dev/null || skip "no oiiotool to read glint's per-view EXRs (Debian package openimageio-tools)"

rm -rf "$work"
mkdir -p "$work"
"$glint" --quiet phantom sphere --size 10 --scheme ico --resolution 5 -o "$work/ico.ply"
"$glint" --quiet phantom sphere --size 10 --scheme ico --resolution 5 \
    --damage "dent:center=10,0,0 radius=1.5 depth=0.3" -o "$work/dent.ply"
"$glint" --quiet phantom sphere --size 10 --scheme uv --resolution 96 -o "$work/uv.ply"
"$glint" --quiet sweep "$work/ico.ply" "$work/dent.ply" --unit mm --zoom 0.1,1,4 --supersample 8 \
    --metric rgb --azimuth-step 90 --elevations 0 --exr --no-views -o "$work/dent"
"$glint" --quiet sweep "$work/ico.ply" "$work/uv.ply" --unit mm --size 128 --azimuth-step 90 \
    --elevations -30,30 --no-views -o "$work/retessellated"
"$python" "$here/report_live_check.py" "$chromium" "$work" "$work/dent" "$work/retessellated"
