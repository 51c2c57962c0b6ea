#!/usr/bin/env bash
# Checkpoint and restart (docs/cli.md "Checkpoints and restart"): for every coupling a run
# interrupted after its checkpoint at step K and continued with `erythro run --restart`
# ends bit for bit where the uninterrupted run of N steps ends: the fields, the cells'
# markers, every diagnostics series and profile of run.h5 (those before K carried over from the
# interrupted run's file) are identical, bit for bit. One run is killed with SIGKILL
# right after its first checkpoint appears. A restart with a changed scene is refused.
set -u
ERYTHRO=$1; SRC=$2; WORK=$3; PYTHON=$4
HERE=$(cd "$(dirname "$0")" && pwd)
rm -rf "$WORK"; mkdir -p "$WORK"; cd "$WORK"
failures=0; checks=0
pass() { checks=$((checks + 1)); echo "ok   $1"; }
fail() { checks=$((checks + 1)); failures=$((failures + 1)); echo "FAIL $1"; }
run() { "$ERYTHRO" run --quiet "$@" > /dev/null; }

# same NAME A B: the fields, cells and diagnostics of two run files are bitwise equal
# (same_run_files.py), and their XDMF indexes identical.
same() {
  local name=$1 a=$2 b=$3 out
  if out=$("$PYTHON" "$HERE/same_run_files.py" "$a" "$b" 2>&1); then
    pass "$name: fields, cells and diagnostics bitwise equal"
  else
    fail "$name: run files differ"; echo "$out" | sed 's/^/    /'
  fi
  if cmp -s "${a%.h5}.xdmf" "${b%.h5}.xdmf"; then pass "$name: run.xdmf identical"; else fail "$name: run.xdmf differs"; fi
}

# The restart runs on RESTART_THREADS OpenMP threads if set (the others on the default).
restart() {
  local name=$1 scene=$2 n=$3 k=$4; shift 4
  run "$scene" --out "$name-full" --set run.steps="$n" "$@" || { fail "$name: uninterrupted run"; return; }
  run "$scene" --out "$name" --set run.steps="$k" --set output.checkpoint_interval_steps="$k" "$@" ||
    { fail "$name: interrupted run"; return; }
  ${RESTART_THREADS:+env OMP_NUM_THREADS=$RESTART_THREADS} "$ERYTHRO" run --quiet --restart "$name" \
    --set run.steps="$n" > /dev/null || { fail "$name: restart"; return; }
  same "$name" "$name-full/run.h5" "$name/run.h5"
}

# K even and odd (the AA pattern's two layouts), between two index-field rebuilds (every 3
# steps) and between two transport steps (every 50).
restart fluid "$SRC/scenes/poiseuille.toml" 400 150 --set output.fields_interval_steps=100
restart cells "$SRC/scenes/capsule_shear.toml" 400 171 --set output.fields_interval_steps=100 \
  --set output.diagnostics_interval_steps=10 --set membrane.interior_viscosity_cP=6.0 \
  --set membrane.index_update_interval=3 --set membrane.area_correction=\"projection\"
restart cells_aggregation "$SRC/verification/aggregation/doublet.toml" 300 131 \
  --set output.fields_interval_steps=100 --set output.diagnostics_interval_steps=10
# Dense cells (26 in the channel): the markers move with the velocity the fluid step writes
# (docs/model.md eq 1.3b), which no checkpoint holds: a step takes it within itself.
restart cells_dense "$SRC/scenes/rbc_channel.toml" 400 171 --set output.fields_interval_steps=100 \
  --set output.diagnostics_interval_steps=10
RESTART_THREADS=1 restart transport_cells "$SRC/solver/tests/cli/checkpoint/transport_cells.toml" 600 320
restart transport_no_fluid "$SRC/scenes/rbc_deoxygenation.toml" 300 110 --set output.fields_interval_steps=100 \
  --set output.diagnostics_interval_steps=10
# An axisymmetric lattice with the [no_o2] compartment reactions (two species, lagged rates).
restart transport_no_o2_axisymmetric "$SRC/scenes/arteriole_no_o2_axisymmetric.toml" 3000 1100 \
  --set output.fields_interval_steps=1000 --set output.diagnostics_interval_steps=100 --set monitor.interval_steps=100

# A cell of revolution with local kinetics (a saturation and a predictor's memory per heme node).
restart transport_local_axisymmetric "$SRC/validation/deoxygenation/deoxygenation_axisymmetric.toml" 400 170 \
  --set domain.spacing_um=0.4 --set domain.size_um=[12,6] --set transport.time_step_s=1e-5 \
  --set output.fields_interval_steps=100 --set output.diagnostics_interval_steps=10 \
  --set output.dense_diagnostics_steps=0 --set monitor.interval_steps=10

# Checkpoints by wall time (one every millisecond): the restart continues from whichever
# step the last one holds.
SCENE="$SRC/scenes/poiseuille.toml"
run "$SCENE" --out wall_time-full --set run.steps=3000 --set output.fields_interval_steps=500
run "$SCENE" --out wall_time --set run.steps=1500 --set output.fields_interval_steps=500 \
  --set output.checkpoint_interval_s=0.001
if run --restart wall_time --set run.steps=3000; then same wall_time wall_time-full/run.h5 wall_time/run.h5
else fail "wall_time: restart"; fi

# A real kill: SIGKILL as soon as the first checkpoint is complete (the rename makes it
# appear whole), then a restart with the unchanged scene.
SCENE="$SRC/scenes/capsule_shear.toml"
SETS=(--set run.steps=4000 --set output.fields_interval_steps=1000 --set output.diagnostics_interval_steps=100)
run "$SCENE" --out killed-full "${SETS[@]}"
"$ERYTHRO" run --quiet "$SCENE" --out killed "${SETS[@]}" --set output.checkpoint_interval_steps=500 > /dev/null &
pid=$!
while kill -0 $pid 2> /dev/null && [[ ! -e killed/checkpoint.h5 ]]; do sleep 0.01; done
if kill -9 $pid 2> /dev/null; then pass "killed: SIGKILL after the first checkpoint"; else echo "note killed: the run ended before the kill"; fi
{ wait $pid; } 2> /dev/null  # no "Killed" notice
if run --restart killed; then same killed killed-full/run.h5 killed/run.h5; else fail "killed: restart"; fi

# A changed scene is refused (exit 2, naming the key); a run length change is not.
out=$("$ERYTHRO" run --quiet --restart fluid --set fluid.viscosity_cP=1.3 2>&1); rc=$?
if [[ $rc -eq 2 && $out == *fluid.viscosity_cP* ]]; then pass "refuse_changed_key"; else fail "refuse_changed_key: exit $rc: $out"; fi
out=$("$ERYTHRO" run --quiet --restart fluid "$SRC/scenes/couette.toml" 2>&1); rc=$?
if [[ $rc -eq 2 && $out == *differs* ]]; then pass "refuse_other_scene"; else fail "refuse_other_scene: exit $rc: $out"; fi
out=$("$ERYTHRO" run --quiet --restart nowhere 2>&1); rc=$?
if [[ $rc -eq 2 && $out == *"no readable checkpoint"* ]]; then pass "refuse_missing_checkpoint"; else fail "refuse_missing_checkpoint: exit $rc: $out"; fi

echo "$checks checks, $failures failures"
[[ $failures -eq 0 ]]
