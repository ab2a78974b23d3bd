#!/usr/bin/env bash
# glint runs from where it is installed, without the build or source tree.
#   install_test.sh prefix|deb CMAKE CPACK BUILD_DIR SOURCE_DIR PYTHON VERSION
# prefix: `cmake --install BUILD --prefix TMP`; deb: CPack's .deb files unpacked with
# `dpkg-deb -x` into a TMP root (their Depends must be installed packages here). Then, in a
# private mount namespace whose view of the source and build folders is an empty tmpfs (when
# `unshare` allows it; else with them in place, said on the output), with an empty environment
# (no LD_LIBRARY_PATH, PATH=/usr/bin:/bin): glint --version, a phantom pair swept with
# --register, the shipped demo scenario, the Slicer module's --xml, and `import glint` from the
# installed Python module (PYTHON none: not built).
set -euo pipefail
mode=$1 cmake=$2 cpack=$3 build=$(realpath "$4") source=$(realpath "$5") python=$6 version=$7
work=$(mktemp -d "${TMPDIR:-/tmp}/glint-install-XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

case "$mode" in
  prefix)
    "$cmake" --install "$build" --prefix "$work/root" >"$work/install.log"
    prefix=$work/root ;;
  deb)
    command -v dpkg-deb >/dev/null || fail "dpkg-deb not found (Debian package dpkg)"
    "$cpack" --config "$build/CPackConfig.cmake" -B "$work/debs" >"$work/cpack.log" 2>&1 ||
      { cat "$work/cpack.log"; fail "cpack"; }
    for deb in "$work"/debs/*.deb; do
      dpkg-deb -I "$deb" | sed -n 's/^ \(Package\|Depends\|Installed-Size\):/  &/p'
      # Every dependency (some alternative of it) is an installed package: what apt would
      # have to provide on a clean machine is named in the package.
      depends=$(dpkg-deb -f "$deb" Depends)
      IFS=',' read -ra groups <<<"$depends"
      for group in "${groups[@]}"; do
        ok=0
        IFS='|' read -ra alternatives <<<"$group"
        for alt in "${alternatives[@]}"; do
          name=$(echo "$alt" | sed 's/(.*//; s/ //g')
          dpkg-query -W -f='${Status}' "$name" 2>/dev/null | grep -q "install ok installed" && ok=1
        done
        [ "$ok" = 1 ] || fail "$(basename "$deb") depends on $group, not installed here"
      done
      dpkg-deb -x "$deb" "$work/root"
    done
    prefix=$work/root/usr ;;
  *) fail "mode $mode: expected prefix or deb" ;;
esac

# Nothing installed points into the build tree (no RPATH/RUNPATH).
for elf in "$prefix/bin/glint" "$prefix"/lib/glint/*.so "$prefix"/lib/python3/dist-packages/glint*.so; do
  [ -e "$elf" ] || continue
  if readelf -d "$elf" | grep -E "RPATH|RUNPATH"; then fail "$elf has a run path"; fi
done
[ -L "$prefix/lib/glint/slicer/glint" ] || fail "no Slicer module link in $prefix/lib/glint/slicer"
[ -f "$prefix/lib/glint/libglint_volume_io.so" ] || fail "no volume plugin in $prefix/lib/glint"
[ -f "$prefix/lib/glint/libglint_image_io.so" ] || fail "no image plugin in $prefix/lib/glint"

cat >"$work/run.sh" <<'INNER'
set -euo pipefail
prefix=$1 work=$2 python=$3 source=$4 build=$5 version=$6
fail() { echo "FAIL: $*"; exit 1; }
[ -z "$(ls -A "$source" 2>/dev/null)" ] && [ -z "$(ls -A "$build" 2>/dev/null)" ] &&
  echo "source and build folders hidden" || echo "note: source and build folders visible (no unshare)"
glint=$prefix/bin/glint
said=$("$glint" --version)
[ "$said" = "glint $version" ] || fail "glint --version said \"$said\", expected \"glint $version\""
echo "$said"
cd "$work"
"$glint" --quiet phantom condyle --scheme ico --resolution 4 -o ref.ply
"$glint" --quiet phantom condyle --scheme uv --resolution 40 --damage "dent:center=2,-1,8.8 radius=3 depth=0.6" \
  --pose "4,-3,5,0.3,-0.2,0.1" -o exa.ply
"$glint" sweep ref.ply exa.ply --register --size 64 --azimuth-step 60 --elevations -45,0,45 --no-exr -o atlas |
  tee sweep.txt
grep -q "1 region(s)" sweep.txt || fail "the installed glint did not find the dent"
"$glint" --quiet run "$prefix/share/glint/scenarios/phantoms/condyle_erosion.toml" -o demo
[ -f demo/condyle-erosion/report.json ] || fail "the demo scenario wrote no report"
# A volume opens the ITK plugin from the installed lib/glint (a 2 x 2 x 2 MetaImage).
printf 'abcdefgh' >tiny.raw
printf 'ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = tiny.raw\n' >tiny.mhd
"$glint" info tiny.mhd | grep -q "size *2 x 2 x 2" || fail "the installed glint read no volume (its plugin in lib/glint)"
xml=$("$prefix/lib/glint/slicer/glint" --xml)
[[ "$xml" == *"<executable>"* ]] || fail "the Slicer module link printed no description"
# The cohort summary inlines glint's page style: the installed copy, not the sources'.
python3 -c "
import os, sys
sys.path.insert(0, '$prefix/share/glint/workflows/cohort')
import summary_html
assert os.path.realpath(summary_html.STYLE_PATH).startswith(os.path.realpath('$prefix')), summary_html.STYLE_PATH
assert '.table-scroll' in summary_html.shared_style()
print('cohort page style:', summary_html.STYLE_PATH)" || fail "the installed cohort summary finds no glint.css"
[ "$python" = none ] && { echo "ok: installed glint ran (no Python module built)"; exit 0; }
PYTHONPATH=$prefix/lib/python3/dist-packages "$python" -c "
import glint, sys
assert glint.__file__.startswith('$prefix'), glint.__file__
a = glint.analyse('ref.ply', 'exa.ply', size=64, azimuth_step=60.0, elevations=[-45.0, 0.0, 45.0])
assert [r['kind'] for r in a.regions] == ['dent'], a.regions
print('python:', glint.__file__, a)
"
echo "ok: installed glint ran"
INNER

# note: env -i drops LD_LIBRARY_PATH and every path into the build; the tmpfs mounts hide the
# source and build folders from the installed programs (a user namespace needs no root).
run=(env -i PATH=/usr/bin:/bin HOME="$work" LANG=C.UTF-8 bash "$work/run.sh" "$prefix" "$work" "$python" "$source" "$build" "$version")
if unshare -rm true 2>/dev/null; then
  hide="mount -t tmpfs none '$source'"
  case "$build" in "$source"/*) ;; *) hide="$hide && mount -t tmpfs none '$build'" ;; esac
  unshare -rm bash -c "$hide && exec \"\$@\"" hide "${run[@]}"
else
  "${run[@]}"
fi
