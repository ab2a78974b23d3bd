#!/usr/bin/env bash
# An interrupted sweep leaves no half-written atlas: SIGINT midway through a long sweep must
# end glint with exit 130, no output folder under the target name and no staged leftovers.
#   interrupt_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/interrupt
rm -rf "$work"
mkdir -p "$work"
"$glint" --quiet phantom condyle --scheme ico --resolution 5 -o "$work/ref.ply" >/dev/null
# ~700 views at 512² with 4×4 sub-samples: far longer than the 3 s before the signal.
set +e
timeout --preserve-status -s INT 3 "$glint" --quiet sweep "$work/ref.ply" "$work/ref.ply" \
    --azimuth-step 2 --elevations -60,-30,0,30,60,90,-90 --size 512 --supersample 4 --no-exr \
    -o "$work/atlas" 2>"$work/stderr.txt"
code=$?
set -e
cat "$work/stderr.txt"
[ "$code" -eq 130 ] || { echo "FAIL: exit $code, expected 130 (interrupted)"; exit 1; }
[ "$(wc -l <"$work/stderr.txt")" -eq 1 ] || { echo "FAIL: expected one line on stderr"; exit 1; }
[ ! -e "$work/atlas" ] || { echo "FAIL: $work/atlas exists after the interrupt"; exit 1; }
left=$(find "$work" -maxdepth 1 -name 'atlas*' | head -1)
[ -z "$left" ] || { echo "FAIL: staged output left behind: $left"; exit 1; }
echo "ok: interrupted sweep exited 130 and left nothing"
