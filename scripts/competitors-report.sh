#!/usr/bin/env bash
# The competitors against the paper's preconditioner, levels 0-2, one sweep per scene
# (reports/competitors-<scene>/): the generic competitors (MUMPS with BLR, PETSc's field
# split, GAMG, the hierarchy with GAMG) beside schur-amg and lu-mumps. COMPETITORS_OUT
# (default reports) and COMPETITORS_TIME_LIMIT (seconds per run, default 1800) adjust it;
# every sweep resumes (--resume), so an interrupted one continues where it stopped. lu-mumps
# at level 2 is refused by its memory guard where MUMPS's own estimate exceeds the machine
# (a row that says so).
# Usage: scripts/competitors-report.sh [build dir] [scene ...]
set -euo pipefail
build=${1:-build}
shift || true
out=${COMPETITORS_OUT:-reports}
limit=${COMPETITORS_TIME_LIMIT:-1800}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
source "$(dirname "$0")/ensure-gnuplot.sh"
competitors() {
  local scene=$1 solvers=$2
  "$build/stiction" bench --scenes "$scene" --solvers "$solvers" --levels 0,1,2 --time-limit "$limit" \
    --out "$out/competitors-$scene" --resume
}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(block-compression hertz-spheres-3d mooney-rivlin-block)
for scene in "${scenes[@]}"; do
  case $scene in
    # No pressure or multiplier block: gamg (one V-cycle on the whole P2 system) applies;
    # fieldsplit-schur has no block to split.
    block-compression) competitors "$scene" lu-mumps,lu-mumps-blr,gamg,schur-gamg,schur-amg ;;
    # Saddle-point systems (multipliers, or the mixed pressure): gamg refuses them at set-up.
    *) competitors "$scene" schur-amg,schur-gamg,fieldsplit-schur,lu-mumps-blr,lu-mumps ;;
  esac
done
echo "competitors-report: wrote $out/competitors-*" >&2
