#!/usr/bin/env bash
# Issue 23 item 6: a folder holding one truncated file aborted inside GDCM (SIGABRT, exit 134)
# in info, surface and sweep; `glint info /proc` aborted the same way. Each must now exit 2 with
# one line saying the folder holds no DICOM series and why.
#   dicom_test.sh GLINT WORKDIR
set -uo pipefail
glint=$1
work=$2/dicom_truncated
rm -rf "$work"
mkdir -p "$work/dcm"
printf '\x08\x00\x05\x00' >"$work/dcm/f"
fail=0
check() {
    local pattern=$1
    shift
    "$@" >"$work/out.txt" 2>"$work/err.txt"
    local code=$?
    cat "$work/err.txt"
    if [ "$code" -ne 2 ] || [ "$(wc -l <"$work/err.txt")" -ne 1 ] || ! grep -Eq "$pattern" "$work/err.txt"; then
        echo "FAIL (exit $code): $*"
        fail=1
    fi
}
found='no DICOM series in it \(1 file\(s\) are not DICOM files; first "f": 4 bytes, expected at least 132'
check "$found" "$glint" info "$work/dcm"
check "$found" "$glint" surface "$work/dcm" --iso 100 -o "$work/s.ply"
check "$found" "$glint" sweep "$work/dcm" "$work/dcm" --iso 100 -o "$work/atlas"
check 'no DICOM series in it' "$glint" info /proc
# fuzz_dicom's first finding: a file whose meta group length (0002,0000) runs past its end
# (GDCM asserted "Should not happen"); beside it a good slice.
mkdir -p "$work/meta"
{ head -c 128 /dev/zero; printf 'DICM\x02\x00\x00\x00UL\x04\x00n\x00d\x00'; } >"$work/meta/b.dcm"
check 'no DICOM series in it .*"b.dcm": file meta group: its length \(0002,0000\) says 6553710 bytes, its elements take 0' \
    "$glint" info "$work/meta"
[ ! -e "$work/s.ply" ] && [ ! -e "$work/atlas" ] || { echo "FAIL: output written"; fail=1; }
[ "$fail" -eq 0 ] && echo "ok: DICOM folders checked before GDCM sees them"
exit "$fail"
