#!/usr/bin/env bash
# Main job: install what is missing, build, run the whole V&V suite (ctest label
# `full`: unit, verification, validation, regression, long studies) and the fluid
# benchmark, then generate the report and print where it is, and rewrite the measured
# sections of docs/verification-*.md and docs/validation-*.md from the new records
# (reports/doc_tables.py --write; commit the pages with the change they document).
# Exits non-zero if any case failed. Prints the expected duration first
# (reports/suite.py expect, from the last recorded times), keeps ctest's per-test times
# in the results folder (*.junit.xml, shown by the report) and in build/timings/full.tsv
# (for the next estimate). To split the suite over machines: ci/vv-shard.sh and ci/vv-merge.sh.
# ERYTHRO_VV_LABEL=study runs the studies instead (ci/study.sh): ctest label `study`, no
# benchmarks, the report in reports-study/, the times left as they are.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_BUILD_DIR:-$root/build}
label=${ERYTHRO_VV_LABEL:-full}
if [[ $label == full ]]; then default_report=$root/reports-out; else default_report=$root/reports-$label; fi
report=${ERYTHRO_REPORT_DIR:-$default_report}
results=$build/results
start=$(date +%s)
"$root/ci/install-deps.sh" || exit 1
"$root/ci/build.sh" || exit 1
[[ $label == full ]] && { /usr/bin/python3 "$root/reports/suite.py" expect --build "$build" -j "$(nproc)" || true; }
rm -f "$results"/*.junit.xml
ctest --test-dir "$build" -L "$label" --output-on-failure -j "$(nproc)" \
  --output-junit "$results/ctest-$label.junit.xml"
tests_status=$?
# Speed against the machine's bandwidth bound, alone on the machine (not in parallel
# with tests), so the report can show it.
if [[ $label == full ]]; then
  ctest --test-dir "$build" -L benchmark --output-on-failure \
    --output-junit "$results/ctest-benchmark.junit.xml" || tests_status=1
  /usr/bin/python3 "$root/reports/suite.py" times "$results/ctest-full.junit.xml" \
    --out "$build/timings/full.tsv" || true
fi
# Only the cases of this tier are required (a `study` case runs in ci/study.sh).
/usr/bin/python3 "$root/reports/generate.py" "$results" --out "$report" --labels "$label"
report_status=$?
# The docs pages' measured sections, from the same records (a case without a record
# keeps its section); a marker that does not fit its record fails the job.
/usr/bin/python3 "$root/reports/doc_tables.py" "$results" --write || report_status=1
echo "report: $report/index.html"
echo "summary: $report/summary.md"
echo "vv.sh ($label) finished in $(( $(date +%s) - start )) s (build included)"
if [[ $tests_status -ne 0 || $report_status -ne 0 ]]; then exit 1; fi
