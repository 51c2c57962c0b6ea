#!/usr/bin/env bash
# Merges the shard folders written by ci/vv-shard.sh into one report:
#   ci/vv-merge.sh OUT DIR...
# A case missing from every folder, or present in two, is an error (docs/reports.md).
# Exits 0 when every case passed, 1 otherwise; prints where the report is.
set -uo pipefail
if [[ $# -lt 2 ]]; then echo "usage: $0 OUT DIR..." >&2; exit 2; fi
root=$(cd "$(dirname "$0")/.." && pwd)
out=$1; shift
/usr/bin/python3 "$root/reports/generate.py" "$@" --out "$out" --labels "${ERYTHRO_SHARD_LABEL:-full}"
status=$?
echo "summary: $out/summary.md"
exit $status
