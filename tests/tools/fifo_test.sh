#!/usr/bin/env bash
# Issue 23 item 11: a FIFO as a mesh or a views file blocked forever in open(); now refused
# at once (exit 2, one line), whoever is or is not writing to it.
#   fifo_test.sh GLINT WORKDIR
set -uo pipefail
glint=$1
work=$2/fifo
cube=$(cd "$(dirname "$0")/../data" && pwd)/cube.obj
rm -rf "$work"
mkdir -p "$work"
mkfifo "$work/mesh.ply" "$work/views.txt"
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
[ "$fail" -eq 0 ] && echo "ok: FIFOs refused without blocking"
exit "$fail"
