# Shared by the shell tests that strike a running glint (tests/faults/fault_suite.sh,
# tests/tools/signals_test.sh); sourced, not run.
#   run_test_setup GLINT WORKDIR PREFIX CASE   sets $glint, $work (WORKDIR/PREFIX_CASE, made
#                                              empty) and $case_name
#   fail MESSAGE…                              one line naming the case, exit 1
#   wait_until_idle PID                        waits until a process's CPU time stands still
#   wait_for_staging TARGET                    waits (up to 30 s) until a run has made its
#                                              staging folder for TARGET: it is past its checks

run_test_setup() {
    glint=$1
    work=$2/$3_$4
    case_name=$4
    rm -rf "$work"
    mkdir -p "$work"
}

fail() {
    echo "FAIL [$case_name]: $*"
    exit 1
}

# wait_until_idle PID: waits (up to 30 s) until the process's CPU time (all its threads) stands
# still for 0.4 s: a run stalled in a step (GLINT_FAULT=…:stall), past its start-up work. A fixed
# sleep was not enough: how soon a run reaches a given step depends on the machine's load.
wait_until_idle() {
    local last=-1 same=0 now
    for _ in $(seq 300); do
        now=$(awk '{print $14 + $15}' "/proc/$1/stat" 2>/dev/null) || fail "process $1 is gone"
        if [ "$now" = "$last" ]; then
            same=$((same + 1))
            [ "$same" -ge 4 ] && return 0
        else
            same=0
        fi
        last=$now
        sleep 0.1
    done
    fail "process $1 never stood still"
}

wait_for_staging() {
    for _ in $(seq 300); do
        compgen -G "$1.partial-*" >/dev/null && return 0
        sleep 0.1
    done
    fail "no staging folder for $1 appeared"
}
