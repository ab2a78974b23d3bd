#!/usr/bin/env bash
# Issue 23, items 1-3 and 19: no command writes over, into or around its inputs. Each case makes
# its own inputs, runs the reproduction and checks the refusal (exit 2, one line naming the
# input) and that every input is byte-identical afterwards.
#   outputs_test.sh GLINT WORKDIR CASE
set -euo pipefail
glint=$1
case_name=$3
work=$2/outputs/$case_name
data=$(cd "$(dirname "$0")/../data" && pwd)
src=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work"
mkdir -p "$work"
cd "$work"
small=(--size 32 --azimuth-step 90 --elevations 0 --no-views --no-exr)

# expect_refused WHAT-REGEX CMD…: exit 2, one line on stderr matching the regex.
expect_refused() {
    local pattern=$1
    shift
    set +e
    "$@" >out.txt 2>err.txt
    local code=$?
    set -e
    cat err.txt
    [ "$code" -eq 2 ] || { echo "FAIL: exit $code, expected 2: $*"; exit 1; }
    [ "$(wc -l <err.txt)" -eq 1 ] || { echo "FAIL: expected one line on stderr"; exit 1; }
    grep -Eq "$pattern" err.txt || { echo "FAIL: stderr does not match '$pattern'"; exit 1; }
}
same() { cmp -s "$1" "$2" || { echo "FAIL: $1 changed"; exit 1; }; }

case $case_name in
sweep_into_input_folder)  # item 1
    mkdir d && cp "$data/cube.obj" d/ref.obj && cp "$data/cube.obj" d/exa.obj
    echo precious >d/notes.txt
    expect_refused 'output "d" contains the input "d/ref.obj"' \
        "$glint" sweep d/ref.obj d/exa.obj "${small[@]}" -o d --force
    same d/ref.obj "$data/cube.obj"; same d/exa.obj "$data/cube.obj"
    [ "$(cat d/notes.txt)" = precious ] || { echo "FAIL: notes.txt lost"; exit 1; }
    [ "$(ls -A | wc -l)" -eq 3 ] || { echo "FAIL: something was left beside d"; ls -A; exit 1; }
    ;;
sweep_into_cwd)  # item 1, -o .
    cp "$data/cube.obj" ref.obj
    expect_refused 'output "\." contains the input' \
        "$glint" sweep ref.obj ref.obj "${small[@]}" -o . --force
    same ref.obj "$data/cube.obj"
    ;;
scenario_name_escapes)  # item 2
    mkdir -p runs victim && echo precious >victim/notes.txt
    for name in '../victim' "$work/victim" '' '.' '..'; do
        sed "s|^name = .*|name = \"$name\"|" "$src/scenarios/phantoms/condyle_bump.toml" >s.toml
        expect_refused 'name: ".*": expected a plain folder name' \
            "$glint" run s.toml -o runs --force
    done
    [ "$(cat victim/notes.txt)" = precious ] || { echo "FAIL: victim replaced"; exit 1; }
    ;;
calibrate_over_scenario)  # item 3
    cp "$src/scenarios/phantoms/condyle_bump.toml" S.toml
    expect_refused 'output "S.toml" is the input "S.toml"' "$glint" calibrate S.toml -o S.toml
    same S.toml "$src/scenarios/phantoms/condyle_bump.toml"
    ;;
compare_over_frame)  # item 3
    "$glint" --quiet render "$data/cube.obj" --size 16 -o f.exr && cp f.exr keep.exr
    expect_refused 'output "f.exr" is the input "f.exr"' "$glint" compare f.exr f.exr -o f.exr
    same f.exr keep.exr
    ;;
volume_edit_over_input)  # item 3, also the raw file of an .mhd
    printf 'ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_UCHAR\nElementSpacing = 1 1 1\nElementDataFile = w.raw\n' >v.mhd
    head -c 64 /dev/urandom >w.raw && cp w.raw keep.raw && cp v.mhd keep.mhd
    expect_refused 'output "v.mhd" is the input "v.mhd"' "$glint" volume-edit v.mhd -o v.mhd
    expect_refused 'output "w.raw" is the input "w.raw"' "$glint" volume-edit v.mhd -o w.mhd
    same v.mhd keep.mhd; same w.raw keep.raw
    ;;
register_over_landmarks)  # item 3
    cp "$data/landmarks_two_pairs.json" L.json
    expect_refused 'output "L.json" is the input "L.json"' \
        "$glint" register "$data/cube.obj" "$data/cube.obj" --landmarks L.json -o L.json
    same L.json "$data/landmarks_two_pairs.json"
    cp "$data/landmarks_two_pairs.json" F.json
    expect_refused 'output "F.json" is the input "F.json"' \
        "$glint" register "$data/cube.obj" "$data/cube.obj" --init F.json -o F.json
    same F.json "$data/landmarks_two_pairs.json"
    ;;
register_apply_together)  # item 19: fit.json and the fitted mesh together or not at all
    set +e
    "$glint" register "$data/cube.obj" "$data/cube.obj" -o f.json --apply moved.xyz 2>err.txt
    code=$?
    set -e
    cat err.txt
    [ "$code" -eq 2 ] || { echo "FAIL: exit $code, expected 2"; exit 1; }
    [ "$(ls -A | grep -v err.txt | wc -l)" -eq 0 ] || { echo "FAIL: left files:"; ls -A; exit 1; }
    ;;
phantom_together)  # item 19: p.ply and p.ply.json together or not at all
    mkdir p.ply.json  # the sidecar cannot be written
    set +e
    "$glint" phantom sphere --resolution 2 -o p.ply 2>err.txt
    code=$?
    set -e
    cat err.txt
    [ "$code" -ne 0 ] || { echo "FAIL: exit 0 with no sidecar"; exit 1; }
    [ ! -e p.ply ] || { echo "FAIL: p.ply written without its sidecar"; exit 1; }
    [ "$(ls -A | grep -v -e err.txt -e p.ply.json | wc -l)" -eq 0 ] || { ls -A; exit 1; }
    "$glint" --quiet phantom sphere --resolution 2 -o q.ply
    [ -f q.ply ] && [ -f q.ply.json ] || { echo "FAIL: the pair was not written"; exit 1; }
    ;;
two_runs_one_new_folder)  # item 4: two runs into one new folder used to both exit 0
    cp "$data/cube.obj" ref.obj
    "$glint" --quiet sweep ref.obj ref.obj "${small[@]}" -o atlas 2>a.err &
    a=$!
    "$glint" --quiet sweep ref.obj ref.obj "${small[@]}" -o atlas 2>b.err &
    b=$!
    set +e
    wait $a; ca=$?
    wait $b; cb=$?
    set -e
    cat a.err b.err
    [ $((ca + cb)) -eq 2 ] && [ $((ca * cb)) -eq 0 ] ||
        { echo "FAIL: exits $ca and $cb, expected one 0 and one 2"; exit 1; }
    grep -Eq 'appeared during the run|exists; give --force' a.err b.err ||
        { echo "FAIL: the refused run does not say why"; exit 1; }
    [ -f atlas/report.json ] || { echo "FAIL: no complete result"; exit 1; }
    [ -z "$(find . -maxdepth 1 -name 'atlas.*')" ] || { echo "FAIL: staging left"; ls -A; exit 1; }
    ;;
# --- issue 52: files an input names, folders glint did not write, bytes that are not UTF-8 ---
roi_mask_inside_output)  # a mask named by --roi / --fit-roi inside -o was deleted by --force
    cp "$data/cube.obj" ref.obj
    "$glint" --quiet sweep ref.obj ref.obj "${small[@]}" -o m
    cp m/atlas.ply m/m.ply
    cp m/m.ply keep.ply
    for flag in --roi --fit-roi; do
        expect_refused 'output ".*m" contains the input ".*m/m\.ply"' \
            "$glint" sweep ref.obj ref.obj "${small[@]}" $flag mask:m/m.ply:seen_z0 -o m --force
        same m/m.ply keep.ply
    done
    ;;
slices_pattern_inside_output)  # ElementDataFile = pattern / LIST: -o slices --force deleted them
    mkdir -p hdr slices sl
    for i in 1 2 3; do printf 'slice %s' $i >slices/CThead.$i; printf 'raw %s' $i >sl/s$i.raw; done
    printf 'ObjectType = Image\nNDims = 3\nDimSize = 2 2 3\nElementType = MET_SHORT\nElementDataFile = ../slices/CThead.%%d 1 3 1\n' >hdr/ct.mhd
    printf 'ObjectType = Image\nNDims = 3\nDimSize = 2 2 3\nElementType = MET_SHORT\nElementDataFile = LIST 2D\n../sl/s1.raw\n../sl/s2.raw\n../sl/s3.raw\n' >hdr/list.mhd
    printf 'NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 3\nencoding: raw\ndata file: ../sl/s%%d.raw 1 3 1 2\n' >hdr/n.nhdr
    cp -r slices slices.keep
    cp -r sl sl.keep
    expect_refused 'output ".*slices" contains the input ".*CThead\.1' \
        "$glint" sweep hdr/ct.mhd hdr/ct.mhd --iso 100 -o slices --force
    for h in hdr/list.mhd hdr/n.nhdr; do
        expect_refused 'output ".*sl" contains the input ".*s1\.raw' \
            "$glint" sweep $h $h --iso 100 -o sl --force
    done
    # volume-edit -o s1.mhd writes s1.raw: the pattern's first slice.
    cp hdr/n.nhdr sl/n.nhdr && sed -i 's|\.\./sl/||' sl/n.nhdr
    expect_refused 'is the input ".*s1\.raw' "$glint" volume-edit sl/n.nhdr -o sl/s1.mhd
    rm sl/n.nhdr
    diff -r slices slices.keep && diff -r sl sl.keep || { echo "FAIL: a slice changed"; exit 1; }
    ;;
gltf_buffers)  # a buffer uri outside the glTF's folder, a FIFO, one inside -o
    mkdir -p g/bins d/bins
    python3 - <<'PY'
import json, struct
pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
idx = struct.pack("<3H", 0, 1, 2) + b"\0\0"
def gltf(uri):
    return json.dumps({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"uri": uri, "byteLength": len(pos) + len(idx)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})
open("g/bins/data.bin", "wb").write(pos + idx)
open("d/bins/data.bin", "wb").write(pos + idx)
open("g/outside.gltf", "w").write(gltf("../g/bins/data.bin"))
open("g/passwd.gltf", "w").write(gltf("/etc/passwd"))
open("g/fifo.gltf", "w").write(gltf("bins/fifo"))
open("d/inside.gltf", "w").write(gltf("bins/data.bin"))
PY
    mkfifo g/bins/fifo
    cp d/bins/data.bin keep.bin
    expect_refused 'glTF buffer 0 uri "\.\./g/bins/data\.bin" names a file outside the glTF.s folder' \
        "$glint" info g/outside.gltf
    expect_refused 'glTF buffer 0 uri "/etc/passwd" names a file outside' "$glint" info g/passwd.gltf
    expect_refused 'is a FIFO, expected a buffer file' timeout 20 "$glint" info g/fifo.gltf
    "$glint" --quiet info d/inside.gltf >/dev/null
    expect_refused 'output ".*bins" contains the input ".*bins/data\.bin' \
        "$glint" sweep d/inside.gltf d/inside.gltf "${small[@]}" -o d/bins --force
    same d/bins/data.bin keep.bin
    ;;
force_over_foreign_folder)  # -o . / -o .. --force replaced any folder that held no input
    mkdir -p home/work
    cp "$data/cube.obj" ref.obj
    echo "years of work" >home/thesis.tex
    echo "notes" >home/work/notes.txt
    (cd home/work && expect_refused 'output folder ".*home/work" exists and holds files glint did not write' \
        "$glint" sweep ../../ref.obj ../../ref.obj "${small[@]}" -o . --force)
    (cd home/work && expect_refused 'output folder ".*home" exists and holds files glint did not write' \
        "$glint" sweep ../../ref.obj ../../ref.obj "${small[@]}" -o .. --force)
    [ "$(cat home/thesis.tex)" = "years of work" ] && [ "$(cat home/work/notes.txt)" = notes ] ||
        { echo "FAIL: the user's files changed"; exit 1; }
    [ "$(ls -A home)" = "$(printf 'thesis.tex\nwork')" ] || { echo "FAIL: staging left"; ls -A home; exit 1; }
    # An earlier result of glint's is still replaced.
    "$glint" --quiet sweep ref.obj ref.obj "${small[@]}" -o atlas
    "$glint" --quiet sweep ref.obj ref.obj "${small[@]}" -o atlas --force
    # A dangling link at -o is named before any work.
    ln -s nowhere link
    expect_refused 'output ".*link" is a symbolic link' "$glint" sweep ref.obj ref.obj "${small[@]}" -o link
    ;;
json_invalid_utf8)  # --json with bytes that are not UTF-8 aborted (SIGABRT)
    for args in "info x$(printf '\377').ply" "frob$(printf '\377')"; do
        set +e
        # shellcheck disable=SC2086
        "$glint" --json $args >out.txt 2>err.txt
        code=$?
        set -e
        cat err.txt
        [ "$code" -eq 2 ] || { echo "FAIL: --json $args: exit $code, expected 2"; exit 1; }
        python3 -c 'import json,sys; d=json.load(open("out.txt")); assert d["exit_code"] == 2, d' ||
            { echo "FAIL: --json $args: stdout is not one JSON error"; cat out.txt; exit 1; }
    done
    # A whole run whose mesh name is not UTF-8 writes its report (json type_error 316 before).
    cp "$data/cube.obj" "r$(printf '\377').obj"
    "$glint" --quiet --json sweep "r$(printf '\377').obj" "r$(printf '\377').obj" "${small[@]}" -o u >out.txt
    python3 -c 'import json; json.load(open("out.txt")); json.load(open("u/report.json"))'
    ;;
escaped_file_names)  # terminal escape sequences in a file name were echoed raw
    cp "$data/cube.obj" "$(printf '\033]0;PWNED\a').obj"
    "$glint" info "$(printf '\033]0;PWNED\a').obj" >out.txt 2>err.txt
    "$glint" info "$(printf '\033]0;PWNED\a')missing.ply" >>out.txt 2>>err.txt || true
    if grep -q "$(printf '\033')" out.txt err.txt || grep -q "$(printf '\a')" out.txt err.txt; then
        echo "FAIL: a control byte reached the terminal"; exit 1
    fi
    grep -q '\\x1b\]0;PWNED\\x07' out.txt && grep -q '\\x1b\]0;PWNED\\x07missing' err.txt ||
        { echo "FAIL: the name is not shown escaped"; cat out.txt err.txt; exit 1; }
    ;;
unclear_words)  # parts far apart, a mesh far out, a plane off the mesh all read "check the fit"
    { sed -n '/^v /p' "$data/cube.obj"; awk '/^v / {print "v", $2 + 1000000, $3, $4}' "$data/cube.obj";
      sed -n '/^f /p' "$data/cube.obj"; sed -n '/^f /p' "$data/cube.obj" |
        awk '{printf "f"; for (i = 2; i <= NF; i++) printf " %d", $i + 8; print ""}'; } >parts.obj
    expect_refused 'reference covers at most [0-9]+ pixels of any of the 4 views' \
        "$glint" sweep parts.obj parts.obj "${small[@]}" -o parts
    sed 's/^v \([^ ]*\) \([^ ]*\) \([^ ]*\)/v 1e30 \2 \3/' "$data/cube.obj" >far.obj
    expect_refused 'lies 1e\+30 units from the origin' "$glint" sweep far.obj far.obj "${small[@]}" -o far
    expect_refused 'symmetry plane .*: lies .* off the surface' \
        "$glint" asymmetry "$data/cube.obj" --plane x=1e12 -o sym
    # A NUL in a scenario's name cut the message there: it is shown escaped, whole.
    sed 's|^name = .*|name = "a\\u0000b/c"|' "$src/scenarios/phantoms/condyle_bump.toml" >n.toml
    expect_refused 'name: "a\\x00b/c": expected a plain folder name' "$glint" run n.toml -o runs
    ;;
*)
    echo "unknown case $case_name"
    exit 1
    ;;
esac
echo "ok: $case_name"
