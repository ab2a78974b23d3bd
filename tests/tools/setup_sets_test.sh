#!/usr/bin/env bash
# tools/setup's package sets (issue 25): the glint program alone (preset app, what tools/demo
# installs) needs none of what only tests, benchmarks or fuzzing use; every other preset
# installs the app set and its own.
set -euo pipefail
root=$1
list() { (cd "$root" && env -u GLINT_VIEWERS -u GLINT_TEST_PACKAGES GLINT_PRESET=$1 tools/setup --list | sort); }
app=$(list app)
fail=0
for p in libgtest-dev libgmock-dev libbenchmark-dev chromium snakemake python3-open3d clang-15 \
         libfuzzer-15-dev clang-format-15 python3-pytest pybind11-dev; do
  if grep -qx "$p" <<<"$app"; then echo "FAIL: the app set holds $p, which only tests, benchmarks or fuzzing use"; fail=1; fi
done
for preset in default ci asan fuzz; do
  missing=$(comm -23 <(echo "$app") <(list "$preset"))
  [ -z "$missing" ] || { echo "FAIL: preset $preset lacks app packages: $missing"; fail=1; }
done
grep -qx libgtest-dev <<<"$(list default)" || { echo "FAIL: the default preset builds tests but does not install libgtest-dev"; fail=1; }
grep -qx clang-15 <<<"$(list fuzz)" || { echo "FAIL: the fuzz preset does not install clang-15"; fail=1; }
# The app preset configures without the test frameworks: it does not build what needs them.
grep -q '"GLINT_BUILD_TESTS": "OFF"' <(python3 -c "
import json; d = json.load(open('$root/CMakePresets.json'))
p = [c for c in d['configurePresets'] if c['name'] == 'app'][0]
print(json.dumps(p['cacheVariables']))") || { echo "FAIL: preset app builds tests"; fail=1; }
[ $fail = 0 ] && echo "ok: app set $(wc -l <<<"$app") packages, none test-only; every preset installs it"
exit $fail
