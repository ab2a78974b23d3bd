#!/usr/bin/env bash
# Issue 23 item 8: a mesh file cut short while glint reads and parses it (another program
# rewriting it) used to end glint with SIGBUS (it was mapped: 12 of 12 attempts). Now the bytes
# are read, so the run ends with the parse of what was read, or one line saying the file
# changed, never a signal.
#   shrinking_input_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/shrinking
rm -rf "$work"
mkdir -p "$work"
"$glint" --quiet phantom sphere --scheme uv --resolution 700 -o "$work/big.ply" >/dev/null
size=$(stat -c %s "$work/big.ply")
for delay in 0 0.3 0.45 0.5 0.55 0.6 0.65 0.7 0.8 1.0; do
    cp "$work/big.ply" "$work/victim.ply"
    set +e
    "$glint" --quiet info "$work/victim.ply" >/dev/null 2>"$work/err.txt" &
    pid=$!
    sleep "$delay"
    truncate -s $((size / 3)) "$work/victim.ply"
    wait "$pid"
    code=$?
    set -e
    [ "$code" -lt 128 ] || { echo "FAIL: cut after ${delay}s: exit $code (a signal): $(cat "$work/err.txt")"; exit 1; }
    [ "$code" -eq 0 ] || [ "$(wc -l <"$work/err.txt")" -eq 1 ] ||
        { echo "FAIL: cut after ${delay}s: exit $code without one line: $(cat "$work/err.txt")"; exit 1; }
    echo "ok: cut to a third after ${delay}s: exit $code $(cat "$work/err.txt")"
done
