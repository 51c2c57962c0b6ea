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
expect check 0 'relaxation time' -- "$ERYTHRO" check "$SCENE"

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
# The XDMF index is well-formed XML and every HDF5 path it names exists in run.h5,
# relative to the XDMF file (so the folder can be moved).
mv run1 run1-moved
expect xdmf_resolves 0 'xdmf ok' -- /usr/bin/python3 -c '
import sys, os, h5py, xml.etree.ElementTree as ET
root = ET.parse("run1-moved/run.xdmf").getroot()
items = [d.text.strip() for d in root.iter("DataItem") if d.get("Format") == "HDF"]
assert items, "no HDF data items"
for item in items:
    fname, path = item.split(":", 1)
    assert not os.path.isabs(fname), item
    with h5py.File(os.path.join("run1-moved", fname), "r") as f:
        assert path in f, item
print("xdmf ok", len(items), "items")'
mv run1-moved run1
expect force_overwrite 0 'results: ' -- "$ERYTHRO" run "$SCENE" --out run1 --quiet --force

# A run whose Mach number passes the monitor's limit (set below the flow's) stops with a diagnosis
# naming step, node and quantity, exit code 3, and a valid file holding the healthy part.
expect diverged 3 'diverged at step [0-9]+: (mach|velocity_x|velocity_y|density) = .* at node \([0-9]+, [0-9]+\)' -- \
  "$ERYTHRO" run "$SCENE" --out diverged --quiet --set monitor.max_mach=3e-5 --set monitor.interval_steps=10
# The regression comparer accepts an identical rerun and catches a small change of
# the discretisation (τ moved by 1e-4), naming the quantity that moved.
TG="$SRC/scenes/regression/taylor_green.toml"
BASE="$SRC/reference_data/baselines/taylor_green.h5"
TOL="$SRC/reference_data/baselines/tolerances.toml"
expect rerun_tg 0 'results: ' -- "$ERYTHRO" run "$TG" --out tg_same --quiet
expect compare_same 0 'all quantities within tolerance' -- "$ERYTHRO" compare tg_same/run.h5 "$BASE" --tolerances "$TOL"
expect rerun_tg_moved 0 'results: ' -- "$ERYTHRO" run "$TG" --out tg_moved --quiet --set time.tau=0.6001
expect compare_moved 5 'MOVED /fields/0000000500/velocity' -- "$ERYTHRO" compare tg_moved/run.h5 "$BASE" --tolerances "$TOL"

checks=$((checks + 1))
if h5dump -a /metadata/status diverged/run.h5 2>/dev/null | grep -q '"diverged"' && h5ls diverged/run.h5/fields >/dev/null 2>&1; then
  echo "ok   diverged_file_valid"; else echo "FAIL diverged run.h5 lacks status or fields"; failures=$((failures + 1)); fi

no_partials no_partial_files

echo "$((checks - failures)) passed, $failures failed"
[[ $failures -eq 0 ]]
