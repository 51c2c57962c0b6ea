#!/usr/bin/env bash
# Main job: install what is missing, build, run the whole V&V suite (ctest label
# `full`: unit, verification, validation, regression, long studies) and the fluid
# benchmark, then generate the report and print where it is. Exits non-zero if any
# case failed.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_BUILD_DIR:-$root/build}
report=${ERYTHRO_REPORT_DIR:-$root/reports-out}
"$root/ci/install-deps.sh" || exit 1
"$root/ci/build.sh" || exit 1
ctest --test-dir "$build" -L full --output-on-failure -j "$(nproc)"
tests_status=$?
# Speed against the machine's bandwidth bound, alone on the machine (not in parallel
# with tests), so the report can show it.
ctest --test-dir "$build" -L benchmark --output-on-failure || tests_status=1
/usr/bin/python3 "$root/reports/generate.py" "$build/results" --out "$report"
report_status=$?
echo "report: $report/index.html"
echo "summary: $report/summary.md"
if [[ $tests_status -ne 0 || $report_status -ne 0 ]]; then exit 1; fi
