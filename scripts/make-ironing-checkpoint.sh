#!/usr/bin/env bash
# Writes tests/data/ironing-2d-L0-t1.675-checkpoint.bin, the restart fixture of
# Ironing.TightKrylovToleranceKeepsTheExactPathWhereSlidingBranches: ironing-2d at level 0,
# solved with schur-amg at the backend's own Krylov tolerance (1e-4) up to load step 145
# (t = 1.675), the step before the one where that tolerance leaves lu-mumps's path.
# Regenerate it whenever the scene's mesh or unknowns change (the test then says the
# checkpoint does not fit). Usage: scripts/make-ironing-checkpoint.sh [build dir]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
if grep -qw avx2 /proc/cpuinfo 2>/dev/null; then export OPENBLAS_CORETYPE=${OPENBLAS_CORETYPE:-Haswell}; fi
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/stiction" solve ironing-2d --level 0 --solver schur-amg --krylov-rtol 0 --until 1.675 --no-vtu --quiet --out "$out"
cp "$out/checkpoint.bin" "$here/tests/data/ironing-2d-L0-t1.675-checkpoint.bin"
echo "wrote tests/data/ironing-2d-L0-t1.675-checkpoint.bin"
