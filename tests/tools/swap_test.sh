#!/usr/bin/env bash
# REF and EXA given the wrong way round: the closed cube as EXA against the open box (the cube
# without its top face) as REF: the examined has 20 % more surface and no region is a loss,
# so glint says the two may be swapped. The right way round (the examined smaller) it says
# nothing of the kind. Warnings go to stderr ("warning: …"), captured here with stdout.
#   swap_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/swap
data=$(cd "$(dirname "$0")/../data" && pwd)
rm -rf "$work"
mkdir -p "$work"
sweep() { "$glint" sweep "$1" "$2" --size 64 --azimuth-step 90 --elevations -45,45 --no-views --no-exr -o "$3"; }

sweep "$data/open_box.obj" "$data/cube.obj" "$work/swapped" >"$work/swapped.txt" 2>&1
cat "$work/swapped.txt"
grep -q "warning: the examined surface is 20% larger .*are REF and EXA swapped" "$work/swapped.txt" ||
    { echo "FAIL: no swap warning for the intact surface given as EXA"; exit 1; }
grep -q "are REF and EXA swapped" "$work/swapped/report.json" || { echo "FAIL: report.json lacks the warning"; exit 1; }

sweep "$data/cube.obj" "$data/open_box.obj" "$work/right" >"$work/right.txt" 2>&1
cat "$work/right.txt"
if grep -q "swapped" "$work/right.txt"; then echo "FAIL: swap warning for the right order"; exit 1; fi
echo "ok: swapped REF/EXA warned about, the right order not"
