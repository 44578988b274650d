#!/usr/bin/env bash
# The bulk-modulus sweep of the Mooney-Rivlin block (issue: nearly incompressible rubber):
# kappa/mu10 = 1e2 .. 1e5 at one mesh level, for the given backends, into OUT/.
#   scripts/kappa-sweep.sh [BUILD] [OUT] [LEVEL] [SOLVERS]
# Writes the scene variants to OUT/scenes/ (each says what it is) and runs stiction bench.
set -euo pipefail
build=${1:-build}
out=${2:-reports/mooney-rivlin-kappa}
level=${3:-0}
solvers=${4:-lu-mumps,schur-lu,schur-amg}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
mkdir -p "$out/scenes"
scenes=()
for kappa in 1e2 1e3 1e4 1e5; do
  value=$(awk -v k="$kappa" 'BEGIN { printf "%.1f", k }')  # mu10 = 1: kappa/mu10 = kappa
  file="$out/scenes/mooney-rivlin-block-kappa-$kappa.toml"
  sed -e "s/^kappa = 100.0/kappa = $value/" \
      -e "s/^name = \"mooney-rivlin-block\"/name = \"mooney-rivlin-block-kappa-$kappa\"/" \
      harness/scenes/mooney-rivlin-block.toml > "$file"
  sed -i "1i # Variant of the built-in mooney-rivlin-block with kappa = $value (kappa/mu10 = $kappa), made by scripts/kappa-sweep.sh." "$file"
  scenes+=("$file")
done
list=$(IFS=,; echo "${scenes[*]}")
"$build/stiction" bench --scenes "$list" --solvers "$solvers" --levels "$level" --out "$out"
