#!/usr/bin/env bash
# The CI tier under AddressSanitizer + UndefinedBehaviorSanitizer (build-sanitize/).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/ci/install-deps.sh"
cmake --preset sanitize -S "$root"
cmake --build "$root/build-sanitize" -j "$(nproc)"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$root/build-sanitize" -L ci -LE regression --output-on-failure -j "$(nproc)"
