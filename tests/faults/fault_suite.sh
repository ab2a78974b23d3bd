#!/usr/bin/env bash
# Fault injection (issue 23): a sweep is struck by a fault at every stage boundary (SIGTERM,
# SIGKILL, a step that never returns), by a full disk at every output step, by a second writer,
# by a folder another program makes at its target, and by address-space limits. After each,
# nothing is lost (the inputs and any previous output byte-identical, or the new output
# complete) and nothing half-written is left (no staging folder or temporary under the
# user's names once the run, or the next one into the same target, has ended).
# Faults are placed with GLINT_FAULT (mesh/fault_injection.h), not raced with a clock.
#   fault_suite.sh GLINT WORKDIR CASE     CASE: stages | disk_full | writers | address_space
set -euo pipefail
source "$(dirname "$0")/../lib/runs.sh"
run_test_setup "$1" "$2" faults "$3"
mkdir -p "$work/in"

"$glint" --quiet phantom condyle --scheme ico --resolution 3 -o "$work/in/ref.ply" >/dev/null
"$glint" --quiet phantom condyle --scheme ico --resolution 4 --pose 2,1,0,0.3,0,0 \
    --damage "dent:center=0,0,10;radius=2.5;depth=0.6" -o "$work/in/exa.ply" >/dev/null
sweep() {
    "$glint" --quiet sweep "$work/in/ref.ply" "$work/in/exa.ply" --register --size 48 \
        --azimuth-step 60 --elevations 0,45 --no-exr --views "$@"
}
# The same run in place of the calling (sub)shell, so that `$!` of `(sweep_exec …) &` is glint.
sweep_exec() {
    exec "$glint" --quiet sweep "$work/in/ref.ply" "$work/in/exa.ply" --register --size 48 \
        --azimuth-step 60 --elevations 0,45 --no-exr --views "$@"
}
digest() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha256sum) | sha256sum | cut -c1-16; }
listing() { (cd "$1" && find . -type f | sort); }
inputs=$(digest "$work/in")

# A clean run: the previous output every fault is tried against, and what a complete one holds.
sweep -o "$work/clean" 2>/dev/null
complete_files=$(listing "$work/clean")
is_complete() { [ -d "$1" ] && [ "$(listing "$1")" = "$complete_files" ]; }
no_leftovers() {
    local left
    left=$(find "$(dirname "$1")" -maxdepth 1 \( -name "$(basename "$1").partial-*" -o -name '.*.tmp-*' \) | head -1)
    [ -z "$left" ] || fail "$2: left behind: $left"
}
# The stderr lines glint wrote about the end of the run (warnings aside).
end_lines() { grep -c '^glint: ' "$1" || true; }


run_fault() {  # run_fault FAULT TARGET [sweep args…]: sets $code, stderr in $work/err.txt
    local fault=$1 target=$2
    shift 2
    set +e
    GLINT_FAULT=$fault sweep -o "$target" "$@" 2>"$work/err.txt"
    code=$?
    set -e
}

case_stages() {
    local stages="${FAULT_STAGES:-fit distance sweep view#1 view#7 decide export file-commit#1 file-commit#9 commit committed}"
    for stage in $stages; do
        for action in term kill; do
            # Over a previous output with --force.
            rm -rf "$work/prev" && cp -a "$work/clean" "$work/prev"
            local before
            before=$(digest "$work/prev")
            run_fault "$stage:$action" "$work/prev" --force
            local what="$stage:$action over a previous output"
            [ "$(digest "$work/in")" = "$inputs" ] || fail "$what: an input changed"
            if [ "$action" = term ]; then
                [ "$code" -eq 130 ] || fail "$what: exit $code, expected 130"
                [ "$(end_lines "$work/err.txt")" -eq 1 ] || fail "$what: expected one line: $(cat "$work/err.txt")"
                no_leftovers "$work/prev" "$what"
            else
                [ "$code" -eq 137 ] || fail "$what: exit $code, expected 137 (killed)"
            fi
            if [ "$stage" = committed ]; then
                is_complete "$work/prev" || fail "$what: the new output is not complete"
                [ "$action" = kill ] || grep -q 'complete and kept' "$work/err.txt" || fail "$what: not said kept"
            else
                [ "$(digest "$work/prev")" = "$before" ] || fail "$what: the previous output changed"
            fi
            if [ "$action" = kill ]; then
                # The next run into the same target removes the killed run's staging folder.
                sweep -o "$work/prev" --force 2>/dev/null || fail "$what: the next run failed"
                is_complete "$work/prev" || fail "$what: the next run's output is not complete"
                no_leftovers "$work/prev" "$what, then a clean run"
            fi

            # Into a new target: absent unless the fault came after the commit.
            rm -rf "$work/new"
            run_fault "$stage:$action" "$work/new"
            what="$stage:$action into a new folder"
            if [ "$stage" = committed ]; then
                is_complete "$work/new" || fail "$what: not complete"
            else
                [ ! -e "$work/new" ] || fail "$what: $work/new exists"
            fi
            [ "$action" = kill ] || no_leftovers "$work/new" "$what"
            echo "ok: $stage:$action (exit $code)"
        done
    done
    # A step that never returns: the watchdog ends the run 3 s after SIGTERM, staging removed.
    for stage in "view#3" decide file-commit#2 commit; do
        rm -rf "$work/prev" && cp -a "$work/clean" "$work/prev"
        local before
        before=$(digest "$work/prev")
        (GLINT_FAULT="$stage:stall" sweep_exec -o "$work/prev" --force 2>"$work/err.txt") &
        local pid=$!
        wait_for_staging "$work/prev"
        sleep 1
        kill -TERM "$pid"
        set +e
        wait "$pid"
        code=$?
        set -e
        local what="$stage:stall, then SIGTERM"
        [ "$code" -eq 130 ] || fail "$what: exit $code, expected 130"
        [ "$(end_lines "$work/err.txt")" -eq 1 ] || fail "$what: expected one line: $(cat "$work/err.txt")"
        [ "$(digest "$work/prev")" = "$before" ] || fail "$what: the previous output changed"
        no_leftovers "$work/prev" "$what"
        echo "ok: $what: $(cat "$work/err.txt")"
    done
}

case_disk_full() {
    # A small tmpfs per size, in a private mount namespace (root, or a user namespace).
    if ! unshare -rm true 2>/dev/null && ! unshare -m true 2>/dev/null; then
        echo "skipped: no mount namespace here (unshare -m refused): the disk-full ladder needs one"
        exit 77
    fi
    local ns="unshare -m"
    unshare -m true 2>/dev/null || ns="unshare -rm"
    local size_kb
    size_kb=$(du -sk "$work/clean" | cut -f1)
    # The previous output takes size_kb; the new one fails at every fraction of its own size.
    for percent in 2 10 25 40 55 70 85 95 150; do
        local limit=$((size_kb + size_kb * percent / 100 + 64))
        $ns bash -s "$glint" "$work" "$limit" <<'INNER' >"$work/ns.txt" 2>&1 || true
set -u
glint=$1 work=$2 limit=$3
mkdir -p "$work/mnt"
mount -t tmpfs -o "size=${limit}k" tmpfs "$work/mnt" || { echo "mount failed"; exit 0; }
cp -a "$work/clean" "$work/mnt/prev"
GLINT_FAULT= "$glint" --quiet sweep "$work/in/ref.ply" "$work/in/exa.ply" --register --size 48 \
    --azimuth-step 60 --elevations 0,45 --no-exr --views -o "$work/mnt/prev" --force 2>"$work/mnt.err"
echo "exit $?"
(cd "$work/mnt/prev" && find . -type f -print0 | sort -z | xargs -0 sha256sum) | sha256sum | cut -c1-16 >"$work/mnt.digest"
(cd "$work/mnt/prev" && find . -type f | sort) >"$work/mnt.listing"
ls -A "$work/mnt" >"$work/mnt.ls"
umount "$work/mnt"
INNER
        grep -q "mount failed" "$work/ns.txt" && { echo "skipped: tmpfs mount refused"; exit 77; }
        local got
        got=$(grep -o 'exit [0-9]*' "$work/ns.txt" | cut -d' ' -f2)
        [ "$(cat "$work/mnt.ls")" = "prev" ] || fail "disk full at +$percent %: left in the folder: $(tr '\n' ' ' <"$work/mnt.ls")"
        if [ "$got" -eq 0 ]; then
            [ "$(cat "$work/mnt.listing")" = "$complete_files" ] || fail "disk full at +$percent %: exit 0 but incomplete"
        else
            [ "$got" -eq 3 ] || fail "disk full at +$percent %: exit $got, expected 3: $(cat "$work/mnt.err")"
            [ "$(end_lines "$work/mnt.err")" -eq 1 ] || fail "disk full at +$percent %: expected one line: $(cat "$work/mnt.err")"
            [ "$(cat "$work/mnt.digest")" = "$(digest "$work/clean")" ] || fail "disk full at +$percent %: the previous output changed"
        fi
        echo "ok: disk full at +$percent % of a new output: exit $got $(head -c 160 "$work/mnt.err")"
    done
    [ "$(digest "$work/in")" = "$inputs" ] || fail "an input changed"
}

case_writers() {
    # Two runs into one new folder, both past their start checks before either commits: one
    # result, complete; the other run refused, naming the folder.
    rm -rf "$work/both"
    GLINT_FAULT=commit:pause sweep -o "$work/both" 2>"$work/err1.txt" &
    local p1=$!
    wait_for_staging "$work/both"
    GLINT_FAULT=commit:pause sweep -o "$work/both" 2>"$work/err2.txt" &
    local p2=$!
    set +e
    wait "$p1"; local c1=$?
    wait "$p2"; local c2=$?
    set -e
    [ $((c1 == 0 ? 1 : 0)) -ne $((c2 == 0 ? 1 : 0)) ] || fail "two writers: exits $c1 and $c2, expected one 0 and one 2"
    [ $((c1 + c2)) -eq 2 ] || fail "two writers: exits $c1 and $c2, expected 0 and 2"
    grep -qh "appeared during the run" "$work/err1.txt" "$work/err2.txt" || fail "two writers: the refusal does not say why"
    is_complete "$work/both" || fail "two writers: the result is not complete"
    no_leftovers "$work/both" "two writers"
    echo "ok: two writers into one new folder: exits $c1 and $c2, one complete result"

    # Both with --force over a previous output: both succeed in turn, the result complete.
    GLINT_FAULT=commit:pause sweep -o "$work/both" --force 2>/dev/null &
    p1=$!
    wait_for_staging "$work/both"
    GLINT_FAULT=commit:pause sweep -o "$work/both" --force 2>/dev/null &
    p2=$!
    wait "$p1" || fail "two --force writers: the first failed"
    wait "$p2" || fail "two --force writers: the second failed"
    is_complete "$work/both" || fail "two --force writers: the result is not complete"
    no_leftovers "$work/both" "two --force writers"
    echo "ok: two --force writers: both replaced the folder in turn, complete"

    # A folder another program makes at the target mid-run is kept as found.
    rm -rf "$work/theirs"
    GLINT_FAULT=commit:pause sweep -o "$work/theirs" 2>"$work/err.txt" &
    p1=$!
    wait_for_staging "$work/theirs"
    mkdir "$work/theirs" && echo "their work" >"$work/theirs/notes.txt"
    set +e
    wait "$p1"
    code=$?
    set -e
    [ "$code" -eq 2 ] || fail "folder made mid-run: exit $code, expected 2"
    [ "$(ls -A "$work/theirs")" = "notes.txt" ] && grep -q "their work" "$work/theirs/notes.txt" ||
        fail "folder made mid-run: its contents changed"
    no_leftovers "$work/theirs" "folder made mid-run"
    echo "ok: a folder made at the target mid-run is kept as found: $(cat "$work/err.txt")"
}

case_address_space() {
    # Under ulimit -v the run completes or ends with one line (exit 3 or 4, never a crash),
    # the previous output untouched and nothing left.
    for mb in 600 1024 1536; do
        rm -rf "$work/prev" && cp -a "$work/clean" "$work/prev"
        local before
        before=$(digest "$work/prev")
        set +e
        (ulimit -v $((mb * 1024)) && exec "$glint" --quiet sweep "$work/in/ref.ply" "$work/in/exa.ply" \
            --register --size 48 --azimuth-step 60 --elevations 0,45 --no-exr --views -o "$work/prev" --force) \
            2>"$work/err.txt"
        code=$?
        set -e
        local what="ulimit -v ${mb} MB"
        [ "$(digest "$work/in")" = "$inputs" ] || fail "$what: an input changed"
        if [ "$code" -eq 0 ]; then
            is_complete "$work/prev" || fail "$what: exit 0 but incomplete"
        else
            [ "$code" -lt 128 ] || fail "$what: exit $code: a crash: $(tail -3 "$work/err.txt")"
            [ "$(end_lines "$work/err.txt")" -eq 1 ] || fail "$what: expected one line: $(cat "$work/err.txt")"
            [ "$(digest "$work/prev")" = "$before" ] || fail "$what: the previous output changed"
        fi
        no_leftovers "$work/prev" "$what"
        echo "ok: $what: exit $code $(grep '^glint: ' "$work/err.txt" | head -c 200)"
    done
    # A default thread stack larger than the address space left (ulimit -s 1 GB under
    # ulimit -v 600 MB): glint's own start-up thread has a stack of its own size. It aborted
    # here before (std::thread's exception, thrown before any command's guard).
    set +e
    (ulimit -v $((600 * 1024)) && ulimit -s 1000000 && exec "$glint" info "$work/in/ref.ply") \
        >/dev/null 2>"$work/err.txt"
    code=$?
    set -e
    [ "$code" -eq 0 ] || fail "ulimit -s 1 GB: glint info exit $code: $(tail -3 "$work/err.txt")"
    echo "ok: a default thread stack beyond the address space: glint info exit 0"
}

case "$case_name" in
    stages) case_stages ;;
    disk_full) case_disk_full ;;
    writers) case_writers ;;
    address_space) case_address_space ;;
    *) fail "unknown case" ;;
esac
echo "ok: fault suite, $case_name"
