#!/usr/bin/env bash
# `-o` onto an existing folder: refused (exit 2, the old results untouched) unless --force,
# and with --force replaced as a whole once the new run completes (nothing staged is left).
#   force_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/force
cube=$(cd "$(dirname "$0")/../data" && pwd)/cube.obj
rm -rf "$work"
mkdir -p "$work"
sweep() { "$glint" --quiet sweep "$cube" "$cube" --size 32 --azimuth-step 90 --elevations 0 --no-views --no-exr "$@"; }

sweep -o "$work/atlas"
echo "marker of the first run" >"$work/atlas/marker.txt"
set +e
sweep -o "$work/atlas" 2>"$work/stderr.txt"
code=$?
set -e
cat "$work/stderr.txt"
[ "$code" -eq 2 ] || { echo "FAIL: exit $code without --force, expected 2"; exit 1; }
grep -q "exists; give --force" "$work/stderr.txt" || { echo "FAIL: the message does not name --force"; exit 1; }
[ -f "$work/atlas/marker.txt" ] || { echo "FAIL: the refused run touched the old folder"; exit 1; }

sweep --force -o "$work/atlas"
[ -f "$work/atlas/report.json" ] || { echo "FAIL: --force left no report.json"; exit 1; }
[ ! -e "$work/atlas/marker.txt" ] || { echo "FAIL: --force merged into the old folder instead of replacing it"; exit 1; }
left=$(find "$work" -maxdepth 1 -name 'atlas.*' | head -1)
[ -z "$left" ] || { echo "FAIL: staged or set-aside folder left behind: $left"; exit 1; }
echo "ok: existing folder refused without --force, replaced whole with it"
