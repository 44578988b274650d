#!/usr/bin/env bash
# Rewrites tests/regression/iterations.csv from a fresh level-0 sweep (short versions, --quick) of every built-in
# scene with every available backend but lu-umfpack (kBackendsOutsideTheBaseline in
# tests/regression/test_iteration_baseline.cpp says why). Run it on purpose (a change that lowers counts, a new scene or
# backend), review the diff, and commit it with the reason in the message.
set -euo pipefail
build=${1:-build}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
solvers=$("$build/stiction" solvers | awk '$2 == "available" && $1 != "lu-umfpack" { print $1 }' | paste -sd,)
"$build/stiction" bench --levels 0 --quick --solvers "$solvers" --out "$tmp/sweep" >&2
out=tests/regression/iterations.csv
{
  echo "# Newton and total Krylov iterations per (scene, backend) at mesh level 0, guarded by"
  echo "# tests/regression/test_iteration_baseline.cpp. Made by scripts/update-iteration-baseline.sh"
  echo "# at git $(git rev-parse --short=12 HEAD) on $(date -u '+%Y-%m-%d')."
  echo "# A run that fails (e.g. boomeramg on an indefinite mixed system) is recorded with its status;"
  echo "# the test then expects the same status and compares no counts."
  echo "scene,solver,status,newton_iterations,krylov_iterations"
  # Columns by name: runs.csv gains columns over time.
  awk -F, '/^#/ { next } !header { for (i = 1; i <= NF; i++) col[$i] = i; header = 1; next }
           { print $col["scene"] "," $col["solver"] "," $col["status"] "," $col["newton_iterations"] "," \
                   $col["krylov_iterations"] }' "$tmp/sweep/runs.csv"
} > "$out"
echo "wrote $out" >&2
