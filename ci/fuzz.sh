#!/usr/bin/env bash
# Fuzzes the `erythro check` path (scene parser, --set overrides, derive_lattice) with
# libFuzzer under AddressSanitizer + UndefinedBehaviorSanitizer, in build-fuzz/ (clang).
#   ci/fuzz.sh            a bounded run: 60 s (ERYTHRO_FUZZ_SECONDS), as ci/test.sh calls it
#   ERYTHRO_FUZZ_SECONDS=3600 ci/fuzz.sh   the longer run of docs/architecture.md, "Fuzzing"
# The seed corpus is scenes/*.toml, copied into build-fuzz/corpus/, where libFuzzer keeps
# what it finds between runs; the dictionary is every table and key name of the schema. A
# crash, a sanitizer report or an exception other than InputError ends the run with a
# non-zero status and leaves the input in build-fuzz/artifacts/ (reproduce it with
# build-fuzz/solver/tests/fuzz/fuzz_scene FILE).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ERYTHRO_FUZZ_BUILD_DIR:-$root/build-fuzz}
seconds=${ERYTHRO_FUZZ_SECONDS:-60}
"$root/ci/install-deps.sh"
# Warnings are the Release build's business (GCC, -Werror); clang's own set is not enforced here.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DERYTHRO_SANITIZE=ON -DERYTHRO_FUZZ=ON -DERYTHRO_WERROR=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target fuzz_scene

mkdir -p "$build/corpus" "$build/artifacts"
cp "$root"/scenes/*.toml "$build/corpus/"
# "name" for every component of every dotted key in the schema (scene_keys.cpp).
grep -oE '\.path = "[a-z_.]+"' "$root/solver/scene/scene_keys.cpp" | cut -d'"' -f2 | tr '.' '\n' |
  sort -u | sed 's/.*/"&"/' > "$build/scene.dict"
printf '"#--set "\n"[["\n"]]"\n"= "\n"nan"\n"inf"\n"1e308"\n"-0.0"\n' >> "$build/scene.dict"

# One process, no forking: the sanitizers' reports and libFuzzer's summary ("Done N runs")
# come out together on stderr. -timeout: an input taking longer is reported as a hang.
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  "$build/solver/tests/fuzz/fuzz_scene" "$build/corpus" -dict="$build/scene.dict" \
  -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 -max_len=16384 \
  -artifact_prefix="$build/artifacts/" -print_final_stats=1
