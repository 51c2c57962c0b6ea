#!/usr/bin/env bash
# The sanitizer tier: the unit tests and one or two fast CI cases per layer under
# AddressSanitizer + UndefinedBehaviorSanitizer (CMake preset `sanitize`, build-sanitize/,
# GCC). It builds only the targets it runs: instrumented code is slow to build and to run,
# so the long cases, the Python tests and the regression baselines (compared bitwise to the
# Release build's numbers) stay in the CI tier. ci/test.sh calls it after that tier.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-sanitize
# The executables of the tests below (a test whose executable is missing fails in ctest).
targets=(erythro unit_common unit_fluid unit_scene unit_io unit_geometry unit_ib unit_membrane unit_interior unit_aggregation
         unit_aggregation_allocation unit_transport unit_analysis vv_fluid vv_membrane vv_interior vv_aggregation
         vv_transport vv_suspension)
tests='^(unit\.(common|fluid|scene|io|cli|scenes_doc_current|geometry|ib|membrane|interior|aggregation'
tests+='|aggregation_allocation|transport|analysis)'
tests+='|verification\.(manufactured|couette|conservation|galilean_symmetry|membrane_rest_in_fluid|membrane_forces'
tests+='|interior_fill_agreement|aggregation_forces|transport_manufactured|transport_hb_coupling|channel_diagnostics'
tests+='|transport_arteriole_no|transport_arteriole_no_o2))$'
start=$(date +%s)
"$root/ci/install-deps.sh"
cmake --preset sanitize -S "$root" >/dev/null
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}"
built=$(date +%s)
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$build" -R "$tests" --output-on-failure -j "$(nproc)"
echo "sanitizer tier: build $(( built - start )) s, tests $(( $(date +%s) - built )) s"
