#!/usr/bin/env bash
# Reruns one regression scene and compares it with its baseline; the comparison
# text (what moved and by how much) is printed and kept for the report.
# usage: run_regression.sh ERYTHRO SCENE BASELINE TOLERANCES WORKDIR REPORT_TXT
set -euo pipefail
erythro=$1 scene=$2 baseline=$3 tolerances=$4 work=$5 report=$6
mkdir -p "$(dirname "$report")"
"$erythro" run "$scene" --out "$work" --force --quiet
set +e
"$erythro" compare "$work/run.h5" "$baseline" --tolerances "$tolerances" | tee "$report"
status=${PIPESTATUS[0]}
exit "$status"
