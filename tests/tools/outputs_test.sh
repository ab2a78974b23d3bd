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
*)
    echo "unknown case $case_name"
    exit 1
    ;;
esac
echo "ok: $case_name"
