# Sourced by the sweep scripts with $default_out set: the sweep's directory ($BENCH_OUT,
# else $default_out) and resume=(--resume) when BENCH_RESUME=1. Nothing is deleted here: a
# new sweep needs a directory without runs.csv (stiction bench refuses one that has it), and
# a committed report is replaced only by scripts/publish-report.sh.
out=${BENCH_OUT:-$default_out}
resume=()
if [ "${BENCH_RESUME:-0}" = 1 ]; then
  resume=(--resume)
elif [ -e "$out/runs.csv" ]; then
  echo "$out already holds a sweep: BENCH_RESUME=1 continues it, BENCH_OUT=<dir> starts a new one" >&2
  exit 2
fi
mkdir -p "$out"
