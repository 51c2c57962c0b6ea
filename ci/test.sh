#!/usr/bin/env bash
# CI tier: install what is missing, build, run the `ci` label of ctest (unit tests,
# fast verification cases, regression checks), then build the report of that tier
# (with ctest's times, from its JUnit output). Then the sanitizer tier (ci/sanitize.sh: the
# unit tests and a few fast cases under ASan + UBSan) and a 60-s fuzzing run of the scene
# input (ci/fuzz.sh), each in its own build folder; ERYTHRO_CI_SANITIZE=0 skips those two.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_BUILD_DIR:-$root/build}
start=$(date +%s)
"$root/ci/install-deps.sh"
"$root/ci/build.sh"
rm -f "$build"/results/*.junit.xml   # the report sums the runs it finds there
ctest --test-dir "$build" -L ci --output-on-failure -j "$(nproc)" \
  --output-junit "$build/results/ctest-ci.junit.xml"
/usr/bin/python3 "$root/reports/generate.py" "$build/results" --out "$build/report-ci" --labels ci
echo "ci tier finished in $(( $(date +%s) - start )) s"
if [[ ${ERYTHRO_CI_SANITIZE:-1} == 1 ]]; then
  "$root/ci/sanitize.sh"
  "$root/ci/fuzz.sh"
  echo "ci tier, sanitizer tier and fuzzing finished in $(( $(date +%s) - start )) s"
fi
