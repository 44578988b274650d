#!/usr/bin/env bash
# The paper's benchmark (`make bench`): Tables 1-3 of Lacasse & Fortin, the block with strips
# (`block-strips`: linear; `block-strips-mr`: Mooney-Rivlin u-p), beside the paper's, from one
# sweep (`stiction bench --sample`) at one revision:
#   * per scene and level, one whole run of schur-amg solves the Newton path and records a
#     fixed sample of its Newton systems (BENCH_SAMPLE, default 2:2,6:1,6:2: load step 2, Newton
#     iteration 2, in the frictionless pressing; iterations 1 and 2 of load step 6, sliding
#     with friction and the grooves closing);
#   * whole runs of lu-mumps at level 0 beside it (BENCH_WHOLE);
#   * every backend (BENCH_SOLVERS, default all) solves the recorded systems in its own process.
# Output, in reports/paper-tables-<revision>/ (BENCH_OUT moves it): report.md, runs.csv (whole
# runs), samples.csv (the sample), steps.csv, growth plots with the paper's points, and the
# contact states at the last load step (the paper's Figures 11 and 12). 83 minutes at
# levels 0-1 on 2 AVX2 cores; BENCH_LEVELS=0,1,2 adds level 2 (not yet timed this way: the
# path run alone, schur-amg's whole run, took 90 minutes and 5.4 GB on an AVX-512 machine).
# BENCH_RESUME=1 continues an interrupted sweep in the same directory (a killed whole run from
# its checkpoint); a binary of another revision is refused unless BENCH_ALLOW_OTHER_REVISION=1.
# BENCH_TIME_LIMIT (seconds per run, default 3600) and BENCH_PETSC_OPTIONS (PETSc options for
# the backends whose prefix they carry) adjust it. scripts/publish-report.sh then replaces
# reports/paper-tables/ with the new directory: an explicit step.
set -euo pipefail
build=${1:-build}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
source "$(dirname "$0")/ensure-gnuplot.sh"

revision=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
git diff --quiet HEAD 2>/dev/null || revision+=-modified
default_out=reports/paper-tables-$revision
source "$(dirname "$0")/sweep-out-dir.sh"

levels=${BENCH_LEVELS:-0,1}
whole=${BENCH_WHOLE:-}
[[ ",$levels," == *,0,* && -z "${BENCH_WHOLE+set}" ]] && whole=lu-mumps:0
args=(--scenes "${BENCH_SCENES:-block-strips,block-strips-mr}" --levels "$levels"
      --sample "${BENCH_SAMPLE:-2:2,6:1,6:2}" --time-limit "${BENCH_TIME_LIMIT:-3600}" --out "$out")
[ -n "$whole" ] && args+=(--whole "$whole")
[ -n "${BENCH_SOLVERS:-}" ] && args+=(--solvers "$BENCH_SOLVERS")
[ "${BENCH_ALLOW_OTHER_REVISION:-0}" = 1 ] && args+=(--allow-other-revision)
read -r -a petsc_options <<< "${BENCH_PETSC_OPTIONS:-}"
start=$(date +%s)
"$build/stiction" bench "${args[@]}" "${resume[@]}" "${petsc_options[@]}"

# Contact states at the last load step of each path run (Debian's python3-matplotlib).
for run in "$out"/runs/block-strips*-schur-amg; do
  [ -f "$run/contact.csv" ] || continue
  name=$(basename "$run")
  /usr/bin/python3 "$(dirname "$0")/render-contact-states.py" "$run/contact.csv" "$out/contact-states-$name.png" \
    --title "$name" || echo "paper-tables: could not render $name" >&2
done
"$build/stiction" report "$out"  # the report shows the PNGs
echo "paper-tables: wrote $out/report.md in $(( ($(date +%s) - start) / 60 )) min" >&2
echo "paper-tables: scripts/publish-report.sh $out reports/paper-tables replaces the committed tables" >&2
