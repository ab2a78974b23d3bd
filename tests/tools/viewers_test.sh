#!/usr/bin/env bash
# The atlas as the viewers people use read it: each check loads glint's files with the real
# program (Debian's meshlab, cloudcompare, python3-vtk9) and compares what it read with what
# glint wrote (viewers_check.py). A program that is not installed is a skip (exit 77) with
# the reason, never a pass.
#   viewers_test.sh GLINT WORKDIR atlas [CT]     make the atlas the checks read (fixture): a
#                                                phantom's; with CT (CThead.mhd, when present)
#                                                also a real CT surface's, with unseen parts
#   viewers_test.sh GLINT WORKDIR vtk|meshlab|cloudcompare
set -euo pipefail
glint=$1
work=$2/viewers
what=$3
here=$(cd "$(dirname "$0")" && pwd)
atlas=$work/atlas
ct_atlas=$work/ct_atlas
skip() { echo "SKIP: $*"; exit 77; }

# A Python that has VTK: the system one (python3-vtk9), also when another python3 is first
# on PATH.
python=python3
for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c "import vtk" 2>/dev/null; then python=$p; break; fi
done

case "$what" in
atlas)
    rm -rf "$work"
    mkdir -p "$work"
    "$glint" --quiet phantom sphere --size 10 --scheme ico --resolution 4 -o "$work/ref.ply"
    "$glint" --quiet phantom sphere --size 10 --scheme ico --resolution 4 \
        --damage "dent:center=10,0,0 radius=3 depth=0.6" -o "$work/exa.ply"
    # Few views, so some vertices stay unseen: they must hold the documented 0 (seen_z0 = 0),
    # never a NaN a viewer chokes on (viewers_check.py checks there are some).
    "$glint" --quiet sweep "$work/ref.ply" "$work/exa.ply" --size 64 --azimuth-step 90 --elevations 20 \
        --no-views --no-exr --atlas-formats ply,vtk,vtp -o "$atlas"
    for f in atlas.ply atlas.vtk atlas.vtp; do [ -s "$atlas/$f" ] || { echo "FAIL: no $f"; exit 1; }; done
    echo "ok: atlas in $atlas"
    ct=${4:-}
    if [ -n "$ct" ] && [ -f "$ct" ]; then
        # A real CT surface (CThead's right condyle, open, with occluded parts) against the
        # same CT with a 3 mm erosion; four views leave about a quarter of it unseen.
        roi=(--iso 1250 --roi sphere:157,113,130,20 --seed 157,113,130 --smooth 10 --edge 1.0)
        "$glint" --quiet surface "$ct" "${roi[@]}" -o "$work/ct_ref.ply"
        "$glint" --quiet volume-edit "$ct" --erode 157,113,130,3 --erode-to 1040 -o "$work/ct_eroded.mha"
        "$glint" --quiet surface "$work/ct_eroded.mha" "${roi[@]}" -o "$work/ct_exa.ply"
        "$glint" --quiet sweep "$work/ct_ref.ply" "$work/ct_exa.ply" --size 64 --azimuth-step 90 \
            --elevations 20 --no-views --unit mm --atlas-formats ply,vtk,vtp -o "$ct_atlas"
        echo "ok: CT atlas in $ct_atlas"
    else
        echo "note: no CT (CThead.mhd) given or found: the MeshLab check runs on the phantom only"
    fi
    ;;
vtk)
    "$python" -c "import vtk" 2>/dev/null || skip "python3 cannot import vtk (Debian package python3-vtk9)"
    "$python" "$here/viewers_check.py" vtk "$atlas"
    ;;
meshlab)
    command -v meshlabserver >/dev/null || skip "meshlabserver not installed (Debian package meshlab)"
    command -v xvfb-run >/dev/null || skip "xvfb-run not installed (Debian package xvfb): meshlabserver needs a display"
    rm -f "$work/meshlab.ply" "$atlas.colorized.ply" "$ct_atlas.colorized.ply"
    # note: meshlabserver 2020.09 needs an OpenGL context even without filters, hence xvfb-run;
    # "-m vc vq" saves vertex colour and quality.
    xvfb-run -a meshlabserver -i "$atlas/atlas.ply" -o "$work/meshlab.ply" -m vc vq >"$work/meshlab.log" 2>&1 ||
        { cat "$work/meshlab.log"; echo "FAIL: meshlabserver failed"; exit 1; }
    [ -s "$work/meshlab.ply" ] || { cat "$work/meshlab.log"; echo "FAIL: meshlabserver wrote nothing"; exit 1; }
    # What README suggests: Filters > Color Creation > Colorize by vertex Quality, on an atlas
    # with unseen vertices (MeshLab aborted there, exit 134, while unseen quality was NaN).
    cat >"$work/colorize.mlx" <<'MLX'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Colorize by vertex Quality">
  <Param type="RichFloat" value="0" name="minVal"/>
  <Param type="RichFloat" value="0" name="maxVal"/>
  <Param type="RichDynamicFloat" value="0" min="0" max="100" name="perc"/>
  <Param type="RichBool" value="true" name="zeroSym"/>
 </filter>
</FilterScript>
MLX
    for dir in "$atlas" "$ct_atlas"; do
        [ -s "$dir/atlas.ply" ] || continue
        rc=0
        xvfb-run -a meshlabserver -i "$dir/atlas.ply" -s "$work/colorize.mlx" -o "$dir.colorized.ply" -m vc vq \
            >"$dir.colorize.log" 2>&1 || rc=$?
        [ "$rc" = 0 ] && [ -s "$dir.colorized.ply" ] ||
            { tail -5 "$dir.colorize.log"; echo "FAIL: MeshLab's Colorize by vertex Quality on $dir/atlas.ply exited $rc"; exit 1; }
        echo "ok: MeshLab colorized $dir/atlas.ply by vertex quality (exit 0)"
    done
    "$python" "$here/viewers_check.py" meshlab "$atlas" "$work/meshlab.ply" "$atlas.colorized.ply"
    if [ -s "$ct_atlas/atlas.ply" ]; then
        "$python" "$here/viewers_check.py" meshlab "$ct_atlas" "$ct_atlas.colorized.ply" "$ct_atlas.colorized.ply"
    fi
    ;;
cloudcompare)
    command -v CloudCompare >/dev/null || skip "CloudCompare not installed (Debian package cloudcompare)"
    command -v xvfb-run >/dev/null || skip "xvfb-run not installed (Debian package xvfb): CloudCompare needs a display"
    for src in ply vtk; do
        rm -f "$work/cc_$src.asc"
        # Open the mesh, take its vertices (with their scalar fields) as a cloud, export as
        # ASCII with a header line naming the fields.
        (cd "$work" && xvfb-run -a CloudCompare -SILENT -NO_TIMESTAMP -AUTO_SAVE OFF -O "$atlas/atlas.$src" \
            -EXTRACT_VERTICES -C_EXPORT_FMT ASC -PREC 9 -ADD_HEADER -SAVE_CLOUDS FILE "cc_$src.asc") \
            >"$work/cc_$src.log" 2>&1 || { cat "$work/cc_$src.log"; echo "FAIL: CloudCompare failed on atlas.$src"; exit 1; }
        if grep -q "not supported\|malformed\|An error occurred" "$work/cc_$src.log"; then
            grep "not supported\|malformed\|error" "$work/cc_$src.log"; echo "FAIL: CloudCompare refused atlas.$src"; exit 1
        fi
        [ -s "$work/cc_$src.asc" ] || { cat "$work/cc_$src.log"; echo "FAIL: CloudCompare exported nothing"; exit 1; }
    done
    "$python" "$here/viewers_check.py" cloudcompare "$atlas" "" "$work/cc_ply.asc" "$work/cc_vtk.asc"
    ;;
*)
    echo "unknown check $what"; exit 2 ;;
esac
