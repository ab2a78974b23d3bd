#!/usr/bin/env bash
# --atlas-formats: a default sweep writes atlas.ply and atlas.vtp (not the legacy atlas.vtk); a
# list writes only
# those named (report.json records which); an unknown or repeated name is refused before any
# work (exit 2, one line naming the option), and no output folder is left.
#   atlas_formats_test.sh GLINT WORKDIR
set -euo pipefail
glint=$1
work=$2/atlas_formats
cube=$(cd "$(dirname "$0")/../data" && pwd)/cube.obj
rm -rf "$work"
mkdir -p "$work"
sweep() { "$glint" --quiet sweep "$cube" "$cube" --size 32 --azimuth-step 90 --elevations 0 --no-views "$@"; }

sweep -o "$work/default"
for f in atlas.ply atlas.vtp; do
  [ -s "$work/default/$f" ] || { echo "FAIL: a default sweep did not write $f"; exit 1; }
done
[ ! -e "$work/default/atlas.vtk" ] || { echo "FAIL: a default sweep wrote the legacy atlas.vtk"; exit 1; }
grep -q '"atlas_files": "ply,vtp"' "$work/default/report.json" ||
  { echo "FAIL: report.json does not record the default atlas_files ply,vtp"; exit 1; }

sweep --atlas-formats ply,vtk,vtp -o "$work/three"
for f in atlas.ply atlas.vtk atlas.vtp; do
  [ -s "$work/three/$f" ] || { echo "FAIL: --atlas-formats ply,vtk,vtp did not write $f"; exit 1; }
done

sweep --atlas-formats vtp,ply -o "$work/two"
[ -s "$work/two/atlas.vtp" ] && [ -s "$work/two/atlas.ply" ] ||
  { echo "FAIL: --atlas-formats vtp,ply did not write both"; ls "$work/two"; exit 1; }
[ ! -e "$work/two/atlas.vtk" ] || { echo "FAIL: --atlas-formats vtp,ply wrote atlas.vtk"; exit 1; }
grep -q '"atlas_files": "ply,vtp"' "$work/two/report.json" ||
  { echo "FAIL: report.json does not record atlas_files ply,vtp"; exit 1; }

for bad in "ply,stl" "vtk,vtk" ""; do
  set +e
  sweep --atlas-formats "$bad" -o "$work/bad" 2>"$work/stderr.txt"
  code=$?
  set -e
  cat "$work/stderr.txt"
  [ "$code" -eq 2 ] || { echo "FAIL: --atlas-formats '$bad' exit $code, expected 2"; exit 1; }
  [ "$(wc -l <"$work/stderr.txt")" -eq 1 ] || { echo "FAIL: expected one line on stderr"; exit 1; }
  grep -q -- "--atlas-formats" "$work/stderr.txt" || { echo "FAIL: the error does not name the option"; exit 1; }
  [ ! -e "$work/bad" ] || { echo "FAIL: a refused command wrote its output folder"; exit 1; }
done
echo "ok: ply and vtp by default, all three when named, only the named ones with --atlas-formats, bad lists refused"
