#!/bin/bash
# Strong scaling, one process against two, on a free machine; one sweep directory per command.
cd "$(git rev-parse --show-toplevel)"
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
B=${STICTION_BIN:?}
run() { echo "== $(date -u +%H:%M:%S) $*" >> "${LOG:-scaling.log}"; $B bench "$@" >> "${LOG:-scaling.log}" 2>&1; }
run --scenes block-strips --solvers schur-amg --levels 1 --ranks 1,2 --time-limit 2400 --out reports/scaling/block-strips-L1
run --scenes block-compression --solvers schur-amg,lu-mumps --levels 1 --ranks 1,2 --time-limit 1800 --out reports/scaling/block-compression-L1
run --scenes mooney-rivlin-block --solvers schur-amg --levels 1 --ranks 1,2 --time-limit 1800 --out reports/scaling/mooney-rivlin-block-L1
run --scenes block-compression --solvers schur-amg --levels 2 --ranks 1,2 --time-limit 2400 --out reports/scaling/block-compression-L2
run --scenes mooney-rivlin-block --solvers schur-amg,lu-mumps --levels 1 --ranks 1,2 --time-limit 1800 --resume --out reports/scaling/mooney-rivlin-block-L1
echo "== $(date -u +%H:%M:%S) done" >> "${LOG:-scaling.log}"
# Level 2, 2026-12-04, binary of 797810e (the ironing run on the other core stopped with SIGSTOP):
run --scenes mooney-rivlin-block --solvers schur-amg --levels 2 --ranks 1,2 --time-limit 2400 --out reports/scaling/mooney-rivlin-block-L2
# block-strips level 2, its first load step only (t = 1: 2 Newton iterations), one and two processes:
#   /usr/bin/time -v [mpirun -n 2] $B solve block-strips --level 2 --until 1 --solver schur-amg --no-vtu \
#     --metrics m.toml --out <dir> -schur_amg_ksp_gmres_restart 50      -> block-strips-L2-first-step/np{1,2}/
# 2026-12-04, binary of 9fdd243's code, free machine (both ironing runs stopped with SIGSTOP):
run --scenes block-strips --solvers schur-amg --levels 2 --ranks 2 --time-limit 6000 --out reports/scaling/block-strips-L2 -schur_amg_ksp_gmres_restart 50
python3 scripts/merge-sweep-runs.py reports/paper-tables reports/scaling/block-strips-L2 block-strips-L2-schur-amg
$B report reports/scaling/block-strips-L2
run --scenes block-strips --solvers schur-amg --levels 1 --ranks 1,2 --time-limit 2400 --out reports/scaling/block-strips-L1
# 2026-12-05, binary of f09580b (stiction solve divides scenes without contact into mesh parts on
# several processes; the ironing run on the other core stopped with SIGSTOP):
run --scenes block-compression,mooney-rivlin-block --solvers schur-amg --levels 1,2 --ranks 1,2 --time-limit 2400 --out reports/scaling/parts-L1-L2
