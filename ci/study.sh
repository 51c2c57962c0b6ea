#!/usr/bin/env bash
# The studies too long for the full tier's 25-minute budget (ctest label `study`, e.g.
# validation.rbc_viscosity_long_runs; each leaves a verdict-bearing subset in `full`):
# ci/vv.sh for that label (install, build, run them, their report in reports-study/, the
# docs tables). Exits non-zero if a case failed.
ERYTHRO_VV_LABEL=study exec "$(dirname "$0")/vv.sh" "$@"
