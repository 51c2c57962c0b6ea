#!/usr/bin/env bash
# Main job: install what is missing, build, run the whole V&V suite (ctest label
# `full`: unit, verification, validation, regression, long studies), then generate
# the report and print where it is. Exits non-zero if any case failed.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_BUILD_DIR:-$root/build}
report=${ERYTHRO_REPORT_DIR:-$root/reports-out}
"$root/ci/install-deps.sh" || exit 1
"$root/ci/build.sh" || exit 1
ctest --test-dir "$build" -L full --output-on-failure -j "$(nproc)"
tests_status=$?
/usr/bin/python3 "$root/reports/generate.py" "$build/results" --out "$report"
report_status=$?
echo "report: $report/index.html"
echo "summary: $report/summary.md"
if [[ $tests_status -ne 0 || $report_status -ne 0 ]]; then exit 1; fi
