#!/usr/bin/env bash
# The paper's benchmark (`make bench`): Tables 2 and 3 of Lacasse & Fortin, the block with
# strips (`block-strips`: linear; `block-strips-mr`: Mooney-Rivlin u-p) under every backend,
# each run in its own process (stiction bench), written to reports/paper-tables/:
#   report.md             Tables 1-3 beside the paper's (reference/lacasse-fortin-block-strips/),
#                         the usual per-scene tables, growth exponents and SVG plots
#   runs.csv, steps.csv   the sweep's rows (kept as runs finish)
#   contact-states-*.png  the deformed strips coloured by contact state at the last load
#                         step (the paper's Figures 11 and 12), from the schur-amg runs
# BENCH_LEVELS (default 0,1; 0,1,2 gives the full tables), BENCH_SCENES (default both),
# BENCH_SOLVERS (default: every backend), BENCH_TIME_LIMIT (seconds per run, default 3600; a
# run it stops gives its figures per linear solve over the solves it finished),
# BENCH_PETSC_OPTIONS (PETSc options for the backends whose prefix they carry; each row
# names those it ran with) and BENCH_RESUME=1 (continue an interrupted sweep, a killed run
# from its checkpoint) adjust it; BENCH_OUT moves it. The level-2 rows, resumable over
# several sittings (about 2 hours per run; the scenes' GMRES(50), newton.krylov_restart,
# keeps schur-amg under 6 GB there):
#   BENCH_LEVELS=2 BENCH_SOLVERS=schur-amg BENCH_RESUME=1 BENCH_TIME_LIMIT=36000 make bench
set -euo pipefail
build=${1:-build}
out=${BENCH_OUT:-reports/paper-tables}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
source "$(dirname "$0")/ensure-gnuplot.sh"

source "$(dirname "$0")/prepare-sweep-dir.sh"
solvers=()
[ -n "${BENCH_SOLVERS:-}" ] && solvers=(--solvers "$BENCH_SOLVERS")
read -r -a petsc_options <<< "${BENCH_PETSC_OPTIONS:-}"
"$build/stiction" bench --scenes "${BENCH_SCENES:-block-strips,block-strips-mr}" --levels "${BENCH_LEVELS:-0,1}" \
  "${solvers[@]}" --time-limit "${BENCH_TIME_LIMIT:-3600}" --out "$out" "${resume[@]}" "${petsc_options[@]}"

# Contact states at the last load step of each schur-amg run (Debian's python3-matplotlib).
for run in "$out"/runs/block-strips*-schur-amg; do
  [ -f "$run/contact.csv" ] || continue
  name=$(basename "$run")
  /usr/bin/python3 "$(dirname "$0")/render-contact-states.py" "$run/contact.csv" "$out/contact-states-$name.png" \
    --title "$name" || echo "paper-tables: could not render $name" >&2
done
"$build/stiction" report "$out"  # the report shows the PNGs
echo "paper-tables: wrote $out/report.md" >&2
