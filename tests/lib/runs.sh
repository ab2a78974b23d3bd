# Shared by the shell tests that strike a running glint (tests/faults/fault_suite.sh,
# tests/tools/signals_test.sh); sourced, not run.
#   run_test_setup GLINT WORKDIR PREFIX CASE   sets $glint, $work (WORKDIR/PREFIX_CASE, made
#                                              empty) and $case_name
#   fail MESSAGE…                              one line naming the case, exit 1
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

wait_for_staging() {
    for _ in $(seq 300); do
        compgen -G "$1.partial-*" >/dev/null && return 0
        sleep 0.1
    done
    fail "no staging folder for $1 appeared"
}
