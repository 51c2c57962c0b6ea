#!/usr/bin/env bash
# One shard of the V&V suite, for a CI matrix or a batch array job:
#   ci/vv-shard.sh K N OUTDIR      (K = 1..N)
# Builds (unless ERYTHRO_SKIP_BUILD=1), runs shard K of the `full` label split into N
# parts of about equal recorded time (reports/suite.py shard: the same split on every
# machine of one commit), and copies this shard's result records, regression texts,
# expected_cases.tsv and ctest's JUnit times into OUTDIR. Shard 1 also runs the
# benchmarks, as ci/vv.sh does. Merge the OUTDIRs with ci/vv-merge.sh. Exits non-zero
# if a test of the shard failed.
set -uo pipefail
if [[ $# -ne 3 ]]; then echo "usage: $0 K N OUTDIR" >&2; exit 2; fi
k=$1 n=$2 out=$3
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_BUILD_DIR:-$root/build}
label=${ERYTHRO_SHARD_LABEL:-full}
results=$build/results
suite=("/usr/bin/python3" "$root/reports/suite.py")
if [[ ${ERYTHRO_SKIP_BUILD:-0} != 1 ]]; then
  "$root/ci/install-deps.sh" || exit 1
  "$root/ci/build.sh" || exit 1
fi
mkdir -p "$out/regression" || exit 1
out=$(cd "$out" && pwd)
rm -f "$out"/*.h5 "$out"/*.junit.xml "$out"/regression/*.txt
mapfile -t tests < <("${suite[@]}" shard "$k" "$n" --build "$build" --label "$label" --list) || exit 2
regex=$("${suite[@]}" shard "$k" "$n" --build "$build" --label "$label") || exit 2
echo "shard $k/$n: ${#tests[@]} tests"
stamp=$(mktemp)   # records older than this are left over from an earlier run
status=0
if [[ ${#tests[@]} -gt 0 ]]; then
  ctest --test-dir "$build" -L "$label" -R "$regex" --output-on-failure -j "$(nproc)" \
    --output-junit "$out/ctest-$label.junit.xml" || status=1
fi
mapfile -t benchmarks < <(ctest --test-dir "$build" -N -L benchmark | sed -n 's/^ *Test *#[0-9]*: //p')
if [[ $k == 1 && $label == full && ${#benchmarks[@]} -gt 0 ]]; then
  ctest --test-dir "$build" -L benchmark --output-on-failure \
    --output-junit "$out/ctest-benchmark.junit.xml" || status=1
  tests+=("${benchmarks[@]}")
fi
for t in "${tests[@]}"; do
  for f in "$results/$t.h5" "$results/regression/${t#regression.}.txt"; do
    if [[ -f $f && $f -nt $stamp ]]; then cp "$f" "$out/${f#"$results"/}"; fi
  done
done
rm -f "$stamp"
cp "$results/expected_cases.tsv" "$out/" 2>/dev/null
echo "shard $k/$n: $(ls "$out"/*.h5 2>/dev/null | wc -l) records in $out"
exit $status
