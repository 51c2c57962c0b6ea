#!/usr/bin/env bash
# End-to-end checks of the erythro command (issue 2 §6, §8, §14): each bad input
# gives a clear message and its documented exit code (docs/cli.md), and leaves no
# partial file behind; an existing run is never overwritten without --force.
set -u
ERYTHRO=$1; SRC=$2; WORK=$3
rm -rf "$WORK"; mkdir -p "$WORK"; cd "$WORK"
failures=0; checks=0
SCENE="$SRC/scenes/poiseuille.toml"

# expect NAME CODE PATTERN -- command...: exit code and a stderr/stdout pattern.
expect() {
  local name=$1 code=$2 pattern=$3; shift 4
  checks=$((checks + 1))
  local out; out=$("$@" 2>&1); local rc=$?
  if [[ $rc -ne $code ]]; then
    echo "FAIL $name: exit $rc, expected $code"; echo "$out" | sed 's/^/    /'; failures=$((failures + 1)); return
  fi
  if ! grep -Eq -- "$pattern" <<<"$out"; then
    echo "FAIL $name: output lacks /$pattern/"; echo "$out" | sed 's/^/    /'; failures=$((failures + 1)); return
  fi
  echo "ok   $name"
}
no_partials() {
  checks=$((checks + 1))
  if find "$WORK" -name '*.partial-*' | grep -q .; then
    echo "FAIL $1: partial files left:"; find "$WORK" -name '*.partial-*'; failures=$((failures + 1))
  else echo "ok   $1"; fi
}

expect version 0 'erythro [0-9.]+ \(git ' -- "$ERYTHRO" --version
expect check 0 'tau' -- "$ERYTHRO" check "$SCENE"

printf '[scene]\nname = "x"\n[domain\nsize_um = 1\n' > malformed.toml
expect malformed_toml 2 'malformed.toml:3' -- "$ERYTHRO" check malformed.toml

sed 's/^viscosity_cP/viscosty_cP/' "$SCENE" > unknown_key.toml
expect unknown_key 2 "unknown_key.toml:[0-9]+.*viscosty_cP.*viscosity_cP" -- "$ERYTHRO" check unknown_key.toml
expect unknown_key_set 2 "fluid.viscosty_cP" -- "$ERYTHRO" check "$SCENE" --set fluid.viscosty_cP=1.0
expect wrong_type 2 "fluid.viscosity_cP" -- "$ERYTHRO" check "$SCENE" --set 'fluid.viscosity_cP="thick"'
expect out_of_range 2 "fluid.viscosity_cP.*-1.*(range|> 0|must be)" -- "$ERYTHRO" check "$SCENE" --set fluid.viscosity_cP=-1
expect tau_too_small 2 "tau.*0.5" -- "$ERYTHRO" check "$SCENE" --set time.tau=0.501
expect missing_scene 2 "cannot read scene file 'nope.toml'" -- "$ERYTHRO" run nope.toml --out missing
checks=$((checks + 1)); if [[ -e missing ]]; then echo "FAIL missing_scene: created output"; failures=$((failures+1)); else echo "ok   missing_scene_no_output"; fi

mkdir -p locked && chmod 500 locked
if [[ $(id -u) -eq 0 ]]; then
  # root ignores permission bits: use a path under a regular file instead.
  touch plainfile
  expect unwritable_output 4 "cannot create output folder" -- "$ERYTHRO" run "$SCENE" --out plainfile/sub --quiet
else
  expect unwritable_output 4 "not writable" -- "$ERYTHRO" run "$SCENE" --out locked --quiet
fi

expect first_run 0 'results: ' -- "$ERYTHRO" run "$SCENE" --out run1 --quiet
cp run1/run.h5 run1.copy.h5
expect refuse_overwrite 4 'already exists.*--force' -- "$ERYTHRO" run "$SCENE" --out run1 --quiet
checks=$((checks + 1))
if cmp -s run1/run.h5 run1.copy.h5; then echo "ok   refused_run_left_file_untouched"; else echo "FAIL refused run changed run1/run.h5"; failures=$((failures+1)); fi
expect force_overwrite 0 'results: ' -- "$ERYTHRO" run "$SCENE" --out run1 --quiet --force

# A run made to diverge (Mach far above the monitor's limit) stops with a diagnosis
# naming step, node and quantity, exit code 3, and a valid file.
expect diverged 3 'diverged at step [0-9]+: (mach|velocity_x|velocity_y|density) = .* at node \([0-9]+, [0-9]+\)' -- \
  "$ERYTHRO" run "$SCENE" --out diverged --quiet --set limits.max_mach=100 --set monitor.max_mach=0.05 --set monitor.interval_steps=1
no_partials no_partial_files

echo "$((checks - failures)) passed, $failures failed"
[[ $failures -eq 0 ]]
