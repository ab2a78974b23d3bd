#!/usr/bin/env bash
# SIGTERM during a slow load ends glint promptly: exit 130 within 1 s of the signal, one line
# on stderr, no output folder and no staged leftovers (issue 16).
# The slow input is a sparse 64 GiB binary PLY whose one element has a list property: every
# item is one zero byte, so the reader walks 2^36 items (minutes) without allocating; only
# the pages it reads before the signal are touched, and the file is removed afterwards.
#   load_interrupt_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/load_interrupt
rm -rf "$work"
mkdir -p "$work"
slow=$work/slow.ply
trap 'rm -f "$slow"' EXIT
printf 'ply\nformat binary_little_endian 1.0\nelement junk 68719476736\nproperty list uchar int x\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n' >"$slow"
truncate -s +64G "$slow"
"$glint" --quiet phantom sphere --resolution 2 -o "$work/ref.ply" >/dev/null

"$glint" --quiet sweep "$slow" "$work/ref.ply" --size 32 -o "$work/atlas" 2>"$work/stderr.txt" &
pid=$!
# Signal once the load has begun: the file is mapped (glint's handlers are installed before
# any command runs). Start-up alone can take a second on a loaded machine.
for _ in $(seq 1 300); do
  grep -q "slow.ply" "/proc/$pid/maps" 2>/dev/null && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
sleep 0.2
kill -0 "$pid" 2>/dev/null || { cat "$work/stderr.txt"; echo "FAIL: glint ended before the signal (the load was not slow)"; exit 1; }
grep -q "slow.ply" "/proc/$pid/maps" || { kill -KILL "$pid"; echo "FAIL: glint did not start loading within 30 s"; exit 1; }
start=$(date +%s%N)
kill -TERM "$pid"
set +e
wait "$pid"
code=$?
set -e
elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
cat "$work/stderr.txt"
[ "$code" -eq 130 ] || { echo "FAIL: exit $code, expected 130 (interrupted)"; exit 1; }
[ "$elapsed_ms" -le 1000 ] || { echo "FAIL: exited ${elapsed_ms} ms after SIGTERM, expected within 1000 ms"; exit 1; }
[ "$(wc -l <"$work/stderr.txt")" -eq 1 ] || { echo "FAIL: expected one line on stderr"; exit 1; }
grep -q "SIGTERM" "$work/stderr.txt" || { echo "FAIL: stderr does not name SIGTERM"; exit 1; }
[ ! -e "$work/atlas" ] || { echo "FAIL: $work/atlas exists after the interrupt"; exit 1; }
left=$(find "$work" -maxdepth 1 -name 'atlas*' | head -1)
[ -z "$left" ] || { echo "FAIL: staged output left behind: $left"; exit 1; }
echo "ok: SIGTERM during loading: exit 130 after ${elapsed_ms} ms, nothing written"
