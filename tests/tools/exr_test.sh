#!/usr/bin/env bash
# Per-view files are opt-in: a default sweep writes no per-view PNG and no EXR, `--views` writes
# one PNG per view, `--exr` one EXR per view with its channels, `--no-exr` (the old opt-out) is still accepted, and
# `--exr --no-exr` together are refused as a command-line mistake (exit 2, one line).
#   exr_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/exr
cube=$(cd "$(dirname "$0")/../data" && pwd)/cube.obj
rm -rf "$work"
mkdir -p "$work"
sweep() { "$glint" --quiet sweep "$cube" "$cube" --size 32 --azimuth-step 90 --elevations 0 "$@"; }

sweep -o "$work/default"
[ -s "$work/default/mosaic_z0.png" ] || { echo "FAIL: default sweep wrote no mosaic"; exit 1; }
n=$(find "$work/default" -path '*/views/*' | wc -l)
[ "$n" -eq 0 ] || { echo "FAIL: default sweep wrote $n per-view files, expected none"; exit 1; }

sweep --views -o "$work/views"
pngs=$(find "$work/views/views" -name '*.png' | wc -l)
exrs=$(find "$work/views/views" -name '*.exr' | wc -l)
[ "$pngs" -eq 4 ] || { echo "FAIL: --views wrote $pngs per-view PNGs, expected 4"; exit 1; }
[ "$exrs" -eq 0 ] || { echo "FAIL: --views wrote $exrs EXRs, expected none"; exit 1; }

sweep --exr -o "$work/exr"
exrs=$(find "$work/exr/views" -name '*.exr' | wc -l)
[ "$exrs" -eq 4 ] || { echo "FAIL: --exr wrote $exrs EXRs, expected 4"; exit 1; }
first=$(find "$work/exr/views" -name '*.exr' | sort | head -1)
if command -v oiiotool >/dev/null; then
  info=$(oiiotool --info -v "$first")
  for channel in angle_deg signed_depth silhouette; do
    grep -q "$channel" <<<"$info" || { echo "FAIL: $first has no channel $channel"; echo "$info"; exit 1; }
  done
fi

sweep --no-exr --no-views -o "$work/no_exr"
[ ! -e "$work/no_exr/views" ] || [ -z "$(ls -A "$work/no_exr/views")" ] ||
  { echo "FAIL: --no-exr --no-views left per-view files"; exit 1; }

set +e
sweep --exr --no-exr -o "$work/both" 2>"$work/stderr.txt"
code=$?
set -e
cat "$work/stderr.txt"
[ "$code" -eq 2 ] || { echo "FAIL: --exr --no-exr exit $code, expected 2"; exit 1; }
[ "$(wc -l <"$work/stderr.txt")" -eq 1 ] || { echo "FAIL: expected one line on stderr"; exit 1; }
[ ! -e "$work/both" ] || { echo "FAIL: a refused command wrote its output folder"; exit 1; }
echo "ok: per-view PNGs only with --views, EXRs only with --exr (4 views), none by default, --no-exr accepted, both refused"
