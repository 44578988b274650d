#!/usr/bin/env bash
# Speed against accuracy (reports/tradeoff/<scene>/): `stiction tradeoff` on a 3D Hertz
# contact scene (errors against the tight reference and against Hertz) and on the block
# without contact, each with the reference one level finer for the discretisation error.
# TRADEOFF_OUT (default reports/tradeoff) and TRADEOFF_TIME_LIMIT (seconds per run, default
# 1200) adjust it; an interrupted report continues with --resume.
# Usage: scripts/tradeoff-report.sh [build dir]
set -euo pipefail
build=${1:-build}
out=${TRADEOFF_OUT:-reports/tradeoff}
limit=${TRADEOFF_TIME_LIMIT:-1200}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
source "$(dirname "$0")/ensure-gnuplot.sh"
mkdir -p "$out"
tradeoff() {
  local scene=$1; shift
  "$build/stiction" tradeoff "$scene" "$@" --newton-rtols 1e-4,1e-6,1e-8 --krylov-rtols 1e-2,1e-4,1e-6 \
    --forcings fixed,eisenstat-walker --discretisation --time-limit "$limit" --out "$out/$scene" --resume
}
tradeoff hertz-sphere-3d --solvers schur-amg,schur-gamg,fieldsplit-schur,lu-mumps \
  --knob schur_amg_ll_pc_hypre_boomeramg_strong_threshold=0.25,0.7 --knob schur_amg_qq_pc_sor_its=2
tradeoff block-compression --solvers schur-amg,schur-gamg,gamg,lu-mumps \
  --knob schur_amg_ll_pc_hypre_boomeramg_strong_threshold=0.25,0.7 --knob schur_amg_qq_pc_sor_its=2
echo "tradeoff-report: wrote $out" >&2
