#!/usr/bin/env bash
# Set-up that cannot silently break (issue 51): every file the app preset's configure and build
# read under /usr belongs to a package in the closure of tools/setup's app set, what tools/demo
# installs on a fresh machine. CI and developers have the test set too, so a package only the
# test set installs (openimageio-tools once: OpenImageIO's CMake configuration checks its tools
# exist) passes every other test and fails a newcomer's first command.
#   app_set_test.sh SOURCE_DIR BUILD_DIR
# BUILD_DIR is the test's own built tree: its deps log gives the headers the compiler read.
set -euo pipefail
root=$1
build=$2
command -v strace >/dev/null || { echo "SKIP: strace not installed (tools/test installs it)"; exit 77; }
command -v dpkg-query >/dev/null || { echo "SKIP: not a Debian system (no dpkg)"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$root" && env -u GLINT_VIEWERS -u GLINT_TEST_PACKAGES GLINT_PRESET=app tools/setup --list) >"$work/app.txt"
# A compiler launcher of the developer's (ccache) is not part of the app's build.
env -u CMAKE_CXX_COMPILER_LAUNCHER -u CMAKE_C_COMPILER_LAUNCHER \
  strace -f -qq -e trace=%file -e status=successful -o "$work/configure.trace" \
  cmake -S "$root" --preset app -B "$work/app" >"$work/configure.log" 2>&1 || {
  echo "FAIL: the app preset does not configure:"; tail -20 "$work/configure.log"; exit 1; }
check() {
  python3 "$root/tests/tools/app_set_check.py" --packages "$1" \
    --configure-trace "$work/configure.trace" --app-dir "$work/app" --deps-dir "$build"
}
check "$work/app.txt"
# The check can fail: without openimageio-tools (the app set before issue 51) it names the package.
grep -vx openimageio-tools "$work/app.txt" >"$work/app_before.txt"
if out=$(check "$work/app_before.txt"); then
  echo "FAIL: the check passes an app set without openimageio-tools, which configure needs"; exit 1
fi
grep -q "package openimageio-tools" <<<"$out" || {
  echo "FAIL: without openimageio-tools the check did not name it:"; echo "$out"; exit 1; }
echo "ok: without openimageio-tools the check fails naming it"
