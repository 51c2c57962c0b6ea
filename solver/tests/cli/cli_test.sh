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
# A membrane torn by a shear far beyond its capillary number (issue 17: this once completed
# with NaN in its diagnostics) stops at the cell health check, exit code 3.
CAPSULE="$SRC/scenes/capsule_shear.toml"
expect torn_membrane 3 'diverged at step [0-9]+: cell 0 (edge strain|area change) = .* exceeds the limit' -- \
  "$ERYTHRO" run "$CAPSULE" --out torn --quiet --set run.steps=600 \
  --set 'boundaries.top.velocity_um_s=[5e5,0]' --set 'boundaries.bottom.velocity_um_s=[-5e5,0]'
# An outward fixed flux far beyond what the medium holds (issue 17: this once completed with O2
# at -2.4e27 uM) stops at the transport's non-negativity floor, exit code 3.
DEOXY="$SRC/scenes/rbc_deoxygenation.toml"
expect drained_o2 3 'diverged at step [0-9]+: O2 concentration = .* is outside its limit .*, below the floor' -- \
  "$ERYTHRO" run "$DEOXY" --out drained --quiet --set run.duration_s=2e-3 --set monitor.interval_steps=20 \
  --set 'species[0].left="fixed_flux"' --set 'species[0].left_value=-1e30'
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

# Scenes with cells ([membrane], [[cells]]): one capsule runs end to end and run.h5
# holds its marker positions; a second cell overlapping the first is refused (exit 2,
# naming the key); a too-stiff membrane is refused with the stability estimate.
CAPSULE="$SRC/scenes/capsule_shear.toml"
expect capsule_check 0 'stability Π_T' -- "$ERYTHRO" check "$CAPSULE"
expect capsule_run 0 'results: ' -- "$ERYTHRO" run "$CAPSULE" --out capsule --quiet
expect capsule_positions 0 'cells ok' -- /usr/bin/python3 -c '
import h5py, numpy as np
with h5py.File("capsule/run.h5", "r") as f:
    assert f["metadata"].attrs["coupling"] == "immersed boundary"
    frames = sorted(f["cells"])
    assert len(frames) >= 2, frames
    for k in frames:
        p = f["cells"][k]["positions"][:]
        assert p.shape == (32, 2) and np.isfinite(p).all(), (k, p.shape)
        assert list(f["cells"][k]["offsets"][:]) == [0, 32]
    r0 = np.hypot(*(p - p.mean(0)).T)
    assert r0.max() - r0.min() > 0.1, "capsule did not deform"
print("cells ok", len(frames), "frames")'
{ cat "$CAPSULE"; printf '\n[[cells]]\nshape = "circle"\nradius_um = 2.0\ncenter_um = [12.5, 5.0]\nmarkers = 32\n'; } > overlap.toml
expect cells_overlap 2 "key 'cells\[1\]\.center_um'.*overlap cell 0" -- "$ERYTHRO" run overlap.toml --out overlap --quiet
checks=$((checks + 1)); if [[ -e overlap ]]; then echo "FAIL cells_overlap: created output"; failures=$((failures+1)); else echo "ok   cells_overlap_no_output"; fi
expect membrane_unstable 2 "membrane.shear_modulus_dyn_cm.*Π_T.*exceeds" -- "$ERYTHRO" check "$CAPSULE" --set membrane.shear_modulus_dyn_cm=1e3

# `erythro schema`: the key reference of docs/scenes.md, generated from the scene schema. A
# stale copy is caught (exit 5, naming the line), --write repairs it and touches nothing else,
# and a page without the marker lines is refused (exit 2).
expect schema_print 0 '### `\[fluid\]`' -- "$ERYTHRO" schema
sed 's/| `1025.0` |/| `1000.0` |/' "$SRC/docs/scenes.md" > stale.md
expect schema_stale 5 'stale.md:[0-9]+: the schema gives' -- "$ERYTHRO" schema --check stale.md
expect schema_stale_hint 5 'erythro schema --write stale.md' -- "$ERYTHRO" schema --check stale.md
expect schema_write 0 'wrote the key reference' -- "$ERYTHRO" schema --write stale.md
expect schema_rewritten 0 'is current' -- "$ERYTHRO" schema --check stale.md
checks=$((checks + 1))
if cmp -s stale.md "$SRC/docs/scenes.md"; then echo "ok   schema_write_restores_page"; else
  echo "FAIL schema --write did not restore the page"; failures=$((failures + 1)); fi
printf '# no markers\n' > unmarked.md
expect schema_no_markers 2 'no generated section' -- "$ERYTHRO" schema --check unmarked.md

# Resources before running (docs/cli.md): `check` prints the estimated memory and output;
# `run` refuses a 1.9e9-node domain that cannot fit in memory, cleanly (exit 2, not an internal
# error or bad_alloc, and no output folder), and warns about 1e6 field snapshots before it
# starts (here the earlier run in run1 then stops it, exit 4, so nothing runs).
expect resources_check 0 'memory \(estimate\)' -- "$ERYTHRO" check "$SCENE"
HUGE=(--set 'domain.size_um=[47500, 40000]' --set domain.spacing_um=1)
expect huge_domain_check 0 'memory \(estimate\) +[0-9.]+ GB' -- "$ERYTHRO" check "$SCENE" "${HUGE[@]}"
if (( $(awk '/^MemAvailable:/ {print int($2 / 1048576)}' /proc/meminfo) < 200 )); then  # GiB
  expect huge_domain_refused 2 'poiseuille.toml: the run needs about [0-9.]+ GB of memory.*--ignore-memory-check' -- \
    "$ERYTHRO" run "$SCENE" "${HUGE[@]}" --out huge --quiet
  checks=$((checks + 1)); if [[ -e huge ]]; then echo "FAIL huge_domain_refused: created output"; failures=$((failures+1)); else echo "ok   huge_domain_no_output"; fi
else
  echo "skip huge_domain_refused: this machine has 200 GiB or more available"
fi
expect large_output_warns 4 'warning: .*taylor_green.toml: the run will write about [0-9.]+ GB.*1e\+06 field snapshots' -- \
  "$ERYTHRO" run "$SRC/scenes/taylor_green.toml" --set run.steps=1000000 --set output.fields_interval_steps=1 \
  --out run1 --quiet

# `erythro dispersion`: a run with cells gives its MSD table; a run without cells is a clear
# input error (exit 2).
ONE="$SRC/verification/suspension/channel_one_cell.toml"
expect one_cell_run 0 'results: ' -- "$ERYTHRO" run "$ONE" --out one_cell --quiet --set run.steps=40 \
  --set output.diagnostics_interval_steps=4
expect dispersion_table 0 'transverse dispersion of 1 cells, 11 samples' -- "$ERYTHRO" dispersion one_cell/run.h5
expect dispersion_no_cells 2 'no cell centroid series' -- "$ERYTHRO" dispersion tg_same/run.h5
# `--across N`: one line per bin between the walls (eq 12.4b); a lag off the samples, or `--lag-s`
# without `--across`, is an input error (exit 2).
expect dispersion_across 0 'across the channel at lag .*picked from the MSD' -- "$ERYTHRO" dispersion one_cell/run.h5 --across 4
expect dispersion_across_bad_lag 2 'lag-s 1e\+09 must be a whole number of sample intervals' -- \
  "$ERYTHRO" dispersion one_cell/run.h5 --across 4 --lag-s 1e9
expect dispersion_lag_needs_across 2 'lag-s requires --across' -- "$ERYTHRO" dispersion one_cell/run.h5 --lag-s 1

# `erythro profiles`: a channel run gives its time-averaged profiles (80 rows) and haematocrits
# (the circle's 448 nodes of 6400: H_t = 0.07); a window past the last sample, or a run that is
# no channel, is an input error (exit 2).
expect profiles_table 0 'time-averaged over 11 samples.*' -- "$ERYTHRO" profiles one_cell/run.h5
expect profiles_rows 0 '^ +19\.875 .*tube haematocrit H_t = 0\.07 ' -- \
  bash -c "\"$ERYTHRO\" profiles one_cell/run.h5 | tail -n 3 | tr '\n' ' '"
expect profiles_window 0 'time-averaged over 6 samples from t = 1\.7' -- "$ERYTHRO" profiles one_cell/run.h5 --after-s 1.7e-7
expect profiles_past_the_end 2 'no sample at or after 1 s' -- "$ERYTHRO" profiles one_cell/run.h5 --after-s 1
expect profiles_no_channel 2 'no profile /profiles/velocity_x_um_s' -- "$ERYTHRO" profiles tg_same/run.h5

# `erythro bench --coupled-only --scene`: a scene it cannot time is an input error (exit 2) with
# the reason, and writes no record.
expect bench_scene_no_cells 2 'needs a scene with cells' -- \
  "$ERYTHRO" bench --coupled-only --scene "$SCENE" --threads 1 --out bench_no_cells.h5
expect bench_scene_no_fluid 2 'times cells in a fluid; this scene has no fluid' -- \
  "$ERYTHRO" bench --coupled-only --scene "$SRC/scenes/rbc_deoxygenation.toml" --threads 1 --out bench_no_fluid.h5
expect bench_scene_malformed 2 'malformed.toml:3' -- \
  "$ERYTHRO" bench --coupled-only --scene malformed.toml --threads 1 --out bench_malformed.h5
expect bench_scene_needs_coupled_only 2 'scene requires --coupled-only' -- \
  "$ERYTHRO" bench --scene "$SRC/scenes/rbc_channel.toml" --out bench_not_coupled.h5
# --alternate-threads compares one thread with more: a single count is refused.
expect bench_alternate_one_count 2 'needs a count of 2 or more in --threads' -- \
  "$ERYTHRO" bench --coupled-only --alternate-threads --cells 2 --threads 1 --out bench_alternate_one.h5
# --grid: one box of NX x NY nodes for every count; cells it cannot hold are an input error
# naming the count, and --grid is not for a scene of one's own.
expect bench_grid_too_small 2 "cell_populations\[0\]\.count' = 40 cannot be reached" -- \
  "$ERYTHRO" bench --coupled-only --cells 40 --grid 64 64 --threads 1 --out bench_grid_small.h5
expect bench_grid_with_scene 2 'grid excludes --scene' -- \
  "$ERYTHRO" bench --coupled-only --scene "$SRC/scenes/rbc_channel.toml" --grid 64 64 --out bench_grid_scene.h5
checks=$((checks + 1))
if ls bench_*.h5 >/dev/null 2>&1; then echo "FAIL bench_scene_refused_no_record: $(ls bench_*.h5)"; failures=$((failures + 1))
else echo "ok   bench_scene_refused_no_record"; fi

no_partials no_partial_files

echo "$((checks - failures)) passed, $failures failed"
[[ $failures -eq 0 ]]
