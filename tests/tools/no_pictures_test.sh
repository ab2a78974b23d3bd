#!/usr/bin/env bash
# --no-pictures (issue 25): a sweep or run that draws no picture never loads the image plugin
# (OpenImageIO and the ~240 libraries Debian builds it with): with a plugin folder that holds
# no plugin it completes, writes no PNG, and its atlas files are byte for byte those of a run
# with pictures (their vertex colours come from the colour maps sampled at build time), with
# report.json recording the choice and report.html saying why it shows no picture; glint run and
# glint asymmetry take the same option.
#   no_pictures_test.sh GLINT WORKDIR EMPTY_PLUGIN_DIR
set -euo pipefail
glint=$1
work=$2/no_pictures
empty_plugins=$3
scenario=$(cd "$(dirname "$0")/../../scenarios/phantoms" && pwd)/condyle_dent.toml
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }

"$glint" --quiet phantom sphere --resolution 4 --size 10 -o "$work/reference.ply"
"$glint" --quiet phantom sphere --resolution 4 --size 10 --damage 'dent:center=0,0,10;radius=3;depth=0.5' \
  -o "$work/examined.ply"
sweep() { "$glint" --quiet sweep "$work/reference.ply" "$work/examined.ply" --size 64 --azimuth-step 60 \
            --elevations -30,30 --atlas-formats ply,vtk,vtp "$@"; }

sweep -o "$work/with"
ls "$work/with"/*.png >/dev/null 2>&1 || fail "a sweep with pictures wrote no PNG"
GLINT_PLUGIN_DIR=$empty_plugins sweep --no-pictures -o "$work/without" ||
  fail "a --no-pictures sweep needed the image plugin"
found=$(find "$work/without" -name '*.png' | head -3)
[ -z "$found" ] || fail "--no-pictures wrote pictures: $found"
for f in atlas.ply atlas.vtk atlas.vtp regions.csv; do
  cmp -s "$work/with/$f" "$work/without/$f" || fail "$f differs between runs with and without pictures"
done
grep -q 'property uchar red' "$work/without/atlas.ply" || fail "atlas.ply has no vertex colours"
grep -q '"pictures": false' "$work/without/report.json" || fail "report.json does not record pictures: false"
grep -q '"pictures": true' "$work/with/report.json" || fail "report.json does not record pictures: true"
[ -s "$work/without/report.html" ] || fail "--no-pictures wrote no report.html"
! grep -q 'data:image/png;base64' "$work/without/report.html" || fail "report.html of --no-pictures embeds a PNG"
grep -q 'data:image/png;base64' "$work/with/report.html" || fail "report.html with pictures embeds no PNG"
# The page's colour scales (the inferno map's 17 colours) are the same with and without.
scale() { grep -o '"sequential":\[[^]]*\]' "$1"; }
[ "$(scale "$work/with/report.html")" = "$(scale "$work/without/report.html")" ] ||
  fail "report.html's sequential colour scale differs without pictures"

# glint run: the same option for scenarios.
GLINT_PLUGIN_DIR=$empty_plugins "$glint" --quiet run "$scenario" --no-pictures -o "$work/runs" ||
  fail "glint run --no-pictures needed the image plugin"
[ -s "$work/runs/condyle-dent/atlas.ply" ] || fail "glint run --no-pictures wrote no atlas"
found=$(find "$work/runs" -name '*.png' | head -3)
[ -z "$found" ] || fail "glint run --no-pictures wrote pictures: $found"
# glint asymmetry: the same option (the export table's), the same promise.
"$glint" --quiet phantom condyle --resolution 4 --damage 'dent:center=6,-3.12,6;radius=2.5;depth=0.4' \
  -o "$work/condyle.ply"
GLINT_PLUGIN_DIR=$empty_plugins "$glint" --quiet asymmetry "$work/condyle.ply" --size 64 --no-pictures \
  -o "$work/asymmetry" > "$work/asymmetry.txt" || fail "glint asymmetry --no-pictures needed the image plugin"
grep -q 'no pictures, report in' "$work/asymmetry.txt" || fail "asymmetry's last line speaks of pictures"
[ -s "$work/asymmetry/atlas.ply" ] && [ -s "$work/asymmetry/report.html" ] || fail "asymmetry wrote no atlas or page"
found=$(find "$work/asymmetry" -name '*.png' | head -3)
[ -z "$found" ] || fail "glint asymmetry --no-pictures wrote pictures: $found"
echo "ok: --no-pictures runs load no image plugin and write the same atlas files"
