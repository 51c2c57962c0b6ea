#!/usr/bin/env bash
# The studies too long for the full tier's 25-minute budget (ctest label `study`, e.g.
# validation.rbc_viscosity_long_runs; each leaves a verdict-bearing subset in `full`):
# install what is missing, build, run them, and write their report (the same report as
# ci/vv.sh, with only the `study` cases required). Exits non-zero if a case failed.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_BUILD_DIR:-$root/build}
report=${ERYTHRO_STUDY_REPORT_DIR:-$root/reports-study}
results=$build/results
start=$(date +%s)
"$root/ci/install-deps.sh" || exit 1
"$root/ci/build.sh" || exit 1
rm -f "$results"/ctest-study.junit.xml
ctest --test-dir "$build" -L study --output-on-failure -j "$(nproc)" \
  --output-junit "$results/ctest-study.junit.xml"
tests_status=$?
/usr/bin/python3 "$root/reports/generate.py" "$results" --out "$report" --labels study
report_status=$?
/usr/bin/python3 "$root/reports/doc_tables.py" "$results" --write || report_status=1
echo "report: $report/index.html"
echo "study.sh finished in $(( $(date +%s) - start )) s (build included)"
if [[ $tests_status -ne 0 || $report_status -ne 0 ]]; then exit 1; fi
