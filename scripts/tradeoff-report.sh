#!/usr/bin/env bash
# Speed against accuracy (reports/tradeoff/<scene>-L<level>/): `stiction tradeoff` on a 3D
# Hertz contact scene (errors against the tight reference and against Hertz, and the
# reference one level finer for the discretisation error), on the block without contact, on
# Cattaneo-Mindlin's partial slip (against Mindlin's stick zone, with coarser meshes) and on
# the block with strips.
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
  local scene=$1 level=$2; shift 2
  "$build/stiction" tradeoff "$scene" --level "$level" "$@" --newton-rtols 1e-4,1e-6,1e-8 --krylov-rtols 1e-2,1e-4,1e-6 \
    --forcings fixed,eisenstat-walker --time-limit "$limit" --out "$out/$scene-L$level" --resume
}
# Level 1 of the sphere (about 25 000 unknowns; its reference one level finer has 170 000):
# at level 0 every run takes under half a second and start-up noise decides the order.
tradeoff hertz-sphere-3d 1 --discretisation --solvers schur-amg,schur-gamg,fieldsplit-schur,lu-mumps \
  --knob schur_amg_ll_pc_hypre_boomeramg_strong_threshold=0.25,0.7 --knob schur_amg_qq_pc_sor_its=2
# The block without contact at level 0 (45 000 unknowns), with the level-1 reference (an
# exact factorisation of 333 000 unknowns: 14 minutes and 7.8 GB).
tradeoff block-compression 0 --discretisation --solvers schur-amg,schur-gamg,gamg,lu-mumps \
  --knob schur_amg_ll_pc_hypre_boomeramg_strong_threshold=0.25,0.7 --knob schur_amg_qq_pc_sor_its=2
# Partial slip against Mindlin's stick zone, level 1, with the mesh as a knob (the backends
# on level 0) and the reference one level finer.
tradeoff cattaneo-mindlin-2d 1 --discretisation --coarser-levels 0 --solvers schur-amg,schur-gamg,lu-mumps
# The paper's benchmark at level 0 (49 482 unknowns and 4 029 multipliers, all 8 load steps:
# friction and the grooves' self-contact from step 5), with the level-1 reference (353 835
# unknowns: about 45 minutes of lu-mumps at 7.5 GB). fieldsplit-schur is left out: about 5x
# schur-amg's time per solve on this scene (reports/paper-tables/report.md, Table 2).
tradeoff block-strips 0 --discretisation --solvers schur-amg,schur-gamg,lu-mumps \
  --knob schur_amg_ll_pc_hypre_boomeramg_strong_threshold=0.25,0.7 --knob schur_amg_qq_pc_sor_its=2
# The cheapening knobs of the backends the sweeps above leave out, at their defaults on the
# sphere: MUMPS's BLR tolerance, the ILU fill level, BoomerAMG's W-cycle (one tolerance pair,
# so every row but the knobs' is a default; ILU(2) takes about 7 minutes).
"$build/stiction" tradeoff hertz-sphere-3d --level 1 --solvers schur-amg,lu-mumps-blr,ilu-gmres --newton-rtols 1e-6 \
  --krylov-rtols 1e-4 --forcings fixed --knob schur_amg_ll_pc_hypre_boomeramg_cycle_type=W \
  --knob lu_mumps_blr_mat_mumps_cntl_7=1e-2,1e-4,1e-6 --knob ilu_gmres_pc_factor_levels=1,2 --time-limit "$limit" \
  --out "$out/hertz-sphere-3d-L1-knobs" --resume
echo "tradeoff-report: wrote $out" >&2
