#!/usr/bin/env bash
# The coupled step of this tree against an earlier commit's, in one paired run (issue 18's
# measure: "one paired run against the efaf88f binary"). Builds the commit's `erythro` once
# (Release, as ci/build.sh; kept in build-against/<commit>/erythro, or $ERYTHRO_AGAINST_DIR),
# builds this tree (ci/build.sh, build/ or $ERYTHRO_BUILD_DIR), then times both on the bench's
# shear boxes with aggregation, in turns (reports/bench_against.py: its options follow the
# commit). Prints a Markdown table; the record goes to <build>/results/bench_against.<commit>.h5.
# Usage: ci/bench-against.sh [COMMIT] [--cells 32 128] [--grid NX NY] [--threads 1 2] [--pairs 3]
# COMMIT defaults to efaf88f. Run it alone on the machine: it measures wall times.
# (docs/performance-coupled-step.md, "One paired run against an earlier commit")
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_BUILD_DIR:-$root/build}
ref=efaf88f
if [[ $# -gt 0 && $1 != -* ]]; then
  ref=$1
  shift
fi
if ! sha=$(git -C "$root" rev-parse --verify --quiet "$ref^{commit}"); then
  echo "ci/bench-against.sh: no commit $ref in this clone (a shallow clone? git fetch --unshallow)" >&2
  exit 2
fi
cache=${ERYTHRO_AGAINST_DIR:-$root/build-against}/$sha
if [[ ! -x $cache/erythro ]]; then
  echo "building $ref ($sha) in $cache"
  rm -rf "$cache/src" "$cache/build"
  mkdir -p "$cache"
  git -C "$root" worktree prune
  # A worktree, not an archive: the build names its own revision (`erythro --version`, the
  # record's reference_version), where an archive inside this clone would take this clone's.
  git -C "$root" worktree add --detach --force "$cache/src" "$sha" > /dev/null 2>&1
  if ! { cmake -S "$cache/src" -B "$cache/build" -DCMAKE_BUILD_TYPE=Release &&
         cmake --build "$cache/build" -j "$(nproc)" --target erythro; } > "$cache/build.log" 2>&1; then
    tail -n 30 "$cache/build.log" >&2
    git -C "$root" worktree remove --force "$cache/src"
    echo "ci/bench-against.sh: $ref did not build (whole log: $cache/build.log)" >&2
    exit 1
  fi
  cp "$cache/build/solver/erythro" "$cache/erythro.partial"
  mv "$cache/erythro.partial" "$cache/erythro"
  git -C "$root" worktree remove --force "$cache/src"
  rm -rf "$cache/build"
fi
"$root/ci/build.sh" > /dev/null
mkdir -p "$build/results"
/usr/bin/python3 "$root/reports/bench_against.py" --reference "$cache/erythro" --this "$build/solver/erythro" \
  --out "$build/results/bench_against.${sha:0:7}.h5" "$@"
