# Sourced by the sweep scripts with $out set: BENCH_RESUME=1 keeps the sweep in $out and
# sets resume=(--resume) for `stiction bench`; otherwise $out starts afresh.
resume=()
if [ "${BENCH_RESUME:-0}" = 1 ]; then
  resume=(--resume)
else
  rm -rf "$out"
fi
mkdir -p "$out"
