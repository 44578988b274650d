#!/bin/bash
# Level-2 block-strips with schur-amg, GMRES(50); restartable from its checkpoint.
# Run in a working folder holding the stiction binary of the revision named in the README.
cd "${1:-.}"
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PETSC_OPTIONS="-schur_amg_ksp_gmres_restart 50"
seg=$(ls -d seg-* 2>/dev/null | wc -l); seg=$((seg+1)); mkdir -p seg-$seg
if [ -f strips-amg/checkpoint.bin ]; then R="--restart strips-amg"; else R="--out strips-amg"; fi
/usr/bin/time -v ./stiction-d5764e7 solve block-strips --level 2 --solver schur-amg --no-vtu \
  --metrics seg-$seg/metrics.toml $R > seg-$seg/stdout 2> seg-$seg/stderr
echo $? > seg-$seg/rc
