#!/usr/bin/env bash
# REF and EXA given the wrong way round: the intact sphere as EXA against a flattened one as
# REF makes every region a gain on a surface 10 % larger than the reference: glint says the
# two may be swapped. Given the right way round it says nothing of the kind.
#   swap_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/swap
rm -rf "$work"
mkdir -p "$work"
"$glint" --quiet phantom sphere --size 10 --scheme ico --resolution 4 -o "$work/intact.ply"
"$glint" --quiet phantom sphere --size 10 --scheme ico --resolution 4 \
    --damage "flatten:center=10,0,0 radius=10 depth=8 normal=1,0,0" -o "$work/cut.ply"
sweep() { "$glint" sweep "$1" "$2" --size 64 --azimuth-step 90 --elevations -30,30 --no-views --no-exr -o "$3"; }

sweep "$work/cut.ply" "$work/intact.ply" "$work/swapped" >"$work/swapped.txt"
cat "$work/swapped.txt"
grep -q "warning: the examined surface is [0-9]*% larger .*are REF and EXA swapped" "$work/swapped.txt" ||
    { echo "FAIL: no swap warning for the intact surface given as EXA"; exit 1; }
grep -q "are REF and EXA swapped" "$work/swapped/report.json" || { echo "FAIL: report.json lacks the warning"; exit 1; }

sweep "$work/intact.ply" "$work/cut.ply" "$work/right" >"$work/right.txt"
cat "$work/right.txt"
if grep -q "swapped" "$work/right.txt"; then echo "FAIL: swap warning for the right order"; exit 1; fi
echo "ok: swapped REF/EXA warned about, the right order not"
