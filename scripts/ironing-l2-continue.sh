#!/usr/bin/env bash
# Continues the level-2 schur-amg ironing runs of reports/ironing-2d-L2 (hours long, chained
# by --restart over several sittings) and brings their state back into the report.
#
#   scripts/ironing-l2-continue.sh start WORK STICTION   # one run per scene in WORK/<variant>/
#   scripts/ironing-l2-continue.sh snapshot WORK          # checkpoints and CSVs -> the report
#
# start: a run directory without a checkpoint gets the report's (checkpoints/schur-amg-
# <variant>.bin with its steps.csv and iterations.csv); each run restarts from its directory
# in the background, one core each (copy the binary out of build/ first, so that a rebuild does
# not change it mid-run; each run gets its own session, so that a SIGSTOP after this script
# has ended does not leave it a stopped orphan, which the kernel hangs up). snapshot: each
# run is stopped (SIGSTOP) while its checkpoint and CSVs are copied into the report, then
# continued; then the force comparison with lu-mumps and the by-level figures are printed
# for the README.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
report=$here/reports/ironing-2d-L2
declare -A scene=([frictional]=ironing-2d [frictionless]=ironing-2d-frictionless)

run_pid() {  # the running solve of a variant's directory, if any
  pgrep -f "solve ${scene[$1]} --level 2 --solver schur-amg --no-vtu --out $2 " || true
}

case "${1:-}" in
  start)
    work=${2:?work directory}
    bin=$(realpath "${3:?stiction binary}")
    for v in frictional frictionless; do
      dir=$(realpath -m "$work/$v")
      mkdir -p "$dir"
      if [[ -n $(run_pid "$v" "$dir") ]]; then echo "$v: already running in $dir"; continue; fi
      if [[ ! -f $dir/checkpoint.bin ]]; then
        cp "$report/checkpoints/schur-amg-$v.bin" "$dir/checkpoint.bin"
        cp "$report/schur-amg-$v-steps.csv" "$dir/steps.csv"
        cp "$report/schur-amg-$v-iterations.csv" "$dir/iterations.csv"
      fi
      [[ -f $dir/run.log ]] && cat "$dir/run.log" >> "$dir/run-earlier.log"
      (cd "$dir" && OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 GLIBC_TUNABLES=glibc.malloc.hugetlb=1 \
        setsid nohup "$bin" solve "${scene[$v]}" --level 2 --solver schur-amg --no-vtu --out "$dir" --restart "$dir" \
        > "$dir/run.log" 2>&1 &)
      echo "$v: started in $dir"
    done
    ;;
  snapshot)
    work=${2:?work directory}
    for v in frictional frictionless; do
      dir=$(realpath -m "$work/$v")
      pid=$(run_pid "$v" "$dir")
      [[ -n $pid ]] && kill -STOP $pid
      cp "$dir/checkpoint.bin" "$report/checkpoints/schur-amg-$v.bin"
      cp "$dir/steps.csv" "$report/schur-amg-$v-steps.csv"
      cp "$dir/iterations.csv" "$report/schur-amg-$v-iterations.csv"
      [[ -n $pid ]] && kill -CONT $pid
      echo "== $v ($([[ -n $pid ]] && echo running || echo not running))"
      (cd "$report" && python3 "$here/scripts/compare-step-forces.py" "schur-amg-$v-steps.csv" "lu-mumps-$v-steps.csv")
    done
    echo "== by level"
    python3 "$here/scripts/ironing-solve-figures.py" "$here/reports"
    ;;
  *)
    sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
    ;;
esac
