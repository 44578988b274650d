#!/usr/bin/env bash
# Rewrites tests/regression/iterations.csv from a fresh level-0 sweep (short versions, --quick) of every built-in
# scene with every available backend but the pairs tests/regression/outside-baseline.csv leaves out (with
# its reasons). Run it on purpose (a change that lowers counts, a new scene or backend), review the diff,
# and commit it with the reason in the message.
set -euo pipefail
build=${1:-build}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
# The BLAS kernels `make test` pins (Makefile: TEST_BLAS_CORE), so that the counts are the
# ones the test will measure on any x86-64 machine with AVX2.
if grep -qw avx2 /proc/cpuinfo 2>/dev/null; then export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}; fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The pairs left out, "scene,solver" separated by ";" (comments and header dropped). Backends
# left out on every scene ("*") are not run at all; the other pairs are dropped below.
outside=$(grep -v '^#' tests/regression/outside-baseline.csv | tail -n +2 | cut -d, -f1,2 | paste -sd';')
solvers=$("$build/stiction" solvers | awk -v outside="$outside" '
  BEGIN { n = split(outside, pairs, ";"); for (i = 1; i <= n; i++) if (pairs[i] ~ /^\*,/) skip[substr(pairs[i], 3)] = 1 }
  $2 == "available" && !($1 in skip) { print $1 }' | paste -sd,)
# BASELINE_JOBS sweeps side by side (default 2, one per core), the scenes dealt round-robin;
# the counts do not depend on how the scenes are grouped.
jobs=${BASELINE_JOBS:-2}
mapfile -t scenes < <("$build/stiction" scenes | awk '{ print $1 }')
pids=()
for ((j = 0; j < jobs; ++j)); do
  part=()
  for ((i = j; i < ${#scenes[@]}; i += jobs)); do part+=("${scenes[i]}"); done
  [ ${#part[@]} -gt 0 ] || continue
  "$build/stiction" bench --levels 0 --quick --scenes "$(IFS=,; echo "${part[*]}")" --solvers "$solvers" \
    --out "$tmp/sweep-$j" >"$tmp/sweep-$j.log" 2>&1 &
  pids+=($!)
done
for j in "${!pids[@]}"; do
  wait "${pids[j]}" || { tail -20 "$tmp/sweep-$j.log" >&2; exit 1; }
done
out=tests/regression/iterations.csv
{
  echo "# Newton and total Krylov iterations per (scene, backend) at mesh level 0, guarded by"
  echo "# tests/regression/test_iteration_baseline.cpp. Made by scripts/update-iteration-baseline.sh"
  echo "# at git $(git rev-parse --short=12 HEAD) on $(date -u '+%Y-%m-%d')."
  echo "# A run that fails (e.g. boomeramg on an indefinite mixed system) is recorded with its status;"
  echo "# the test then expects the same status and compares no counts."
  echo "scene,solver,status,newton_iterations,krylov_iterations"
  # Columns by name (runs.csv gains columns over time), each sweep's header read from its own file.
  awk -F, -v outside="$outside" '
    BEGIN { n = split(outside, pairs, ";"); for (i = 1; i <= n; i++) out[pairs[i]] = 1 }
    /^#/ { next } !(FILENAME in header) { for (i = 1; i <= NF; i++) col[$i] = i; header[FILENAME] = 1; next }
    (($col["scene"] "," $col["solver"]) in out) { next }
    { print $col["scene"] "," $col["solver"] "," $col["status"] "," $col["newton_iterations"] "," \
                   $col["krylov_iterations"] }' "$tmp"/sweep-*/runs.csv | sort -t, -k1,1 -k2,2
} > "$out"
echo "wrote $out" >&2
