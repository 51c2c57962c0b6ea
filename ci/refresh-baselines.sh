#!/usr/bin/env bash
# Refreshes the regression baselines ON PURPOSE, after a change whose effect on the
# results has been understood. Reruns every scenes/regression/*.toml and copies its
# run.h5 to reference_data/baselines/NAME.h5. Review `git diff --stat` and say why
# in the commit message.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_BUILD_DIR:-$root/build}
"$root/ci/build.sh" >/dev/null
for scene in "$root"/scenes/regression/*.toml; do
  name=$(basename "$scene" .toml)
  out="$build/baseline-refresh/$name"
  "$build/solver/erythro" run "$scene" --out "$out" --force --quiet
  cp "$out/run.h5" "$root/reference_data/baselines/$name.h5"
  echo "refreshed reference_data/baselines/$name.h5"
done
