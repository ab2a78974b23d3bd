#!/usr/bin/env bash
# Issue 23 item 11: a FIFO as a mesh or a views file blocked forever in open(); now refused
# at once (exit 2, one line), whoever is or is not writing to it. So are FIFOs, folders and
# devices given as the small files (fit, landmarks, --init, scenario): a FIFO hung until the
# watchdog ended glint, a folder ended in "internal error: basic_filebuf::underflow …".
#   fifo_test.sh GLINT WORKDIR
set -uo pipefail
glint=$1
work=$2/fifo
cube=$(cd "$(dirname "$0")/../data" && pwd)/cube.obj
rm -rf "$work"
mkdir -p "$work"
mkfifo "$work/mesh.ply" "$work/views.txt" "$work/fit.json" "$work/scenario.toml"
mkdir -p "$work/folder.json" "$work/in"
cp "$cube" "$work/in/cube.obj"
fail=0
check() {
    local pattern=$1
    shift
    timeout 20 "$@" >"$work/out.txt" 2>"$work/err.txt"
    local code=$?
    cat "$work/err.txt"
    if [ "$code" -ne 2 ] || [ "$(wc -l <"$work/err.txt")" -ne 1 ] || ! grep -Eq "$pattern" "$work/err.txt"; then
        echo "FAIL (exit $code): $*"
        fail=1
    fi
}
check 'mesh.ply": is a FIFO, expected a regular mesh file' "$glint" info "$work/mesh.ply"
check 'views.txt": not a regular file' "$glint" render "$cube" --views-file "$work/views.txt" -o "$work/v.png"
in=$work/in/cube.obj
check 'fit ".*fit.json": is a FIFO, expected a file' "$glint" sweep "$in" "$in" --fit "$work/fit.json" -o "$work/out"
check 'fit ".*folder.json": is a folder, expected a file' "$glint" sweep "$in" "$in" --fit "$work/folder.json" -o "$work/out"
check 'fit "/dev/zero": is a character device, expected a file' "$glint" sweep "$in" "$in" --fit /dev/zero -o "$work/out"
check 'landmarks ".*folder.json": is a folder, expected a file' "$glint" register "$in" "$in" --landmarks "$work/folder.json" -o "$work/f.json"
check 'fit ".*fit.json": is a FIFO, expected a file' "$glint" register "$in" "$in" --init "$work/fit.json" -o "$work/f.json"
check 'scenario ".*scenario.toml": is a FIFO, expected a file' "$glint" run "$work/scenario.toml"
check 'scenario ".*scenario.toml": is a FIFO, expected a file' "$glint" calibrate "$work/scenario.toml" -o "$work/c.toml"
[ ! -e "$work/out" ] && [ ! -e "$work/f.json" ] || { echo "FAIL: output written"; fail=1; }
[ "$fail" -eq 0 ] && echo "ok: FIFOs refused without blocking"
exit "$fail"
