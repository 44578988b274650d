#!/usr/bin/env bash
# `make bench-all`: the sweep of every built-in scene (x every backend x mesh levels 0 and
# 1, each run in its own process) and the micro-benchmarks, written to reports/latest/
# (`make bench` runs the paper's tables instead: scripts/paper-tables.sh):
#   report.md, runs.csv, steps.csv, runs/<run>/   the sweep (stiction bench)
#   micro-benchmarks.txt / .json                   assembly, SpMV, backend set-up and apply
# The large-sliding scenes (hundreds of load steps each) and the block with strips are left
# out of the sweep and run by their own reports instead (reports/paper-tables/:
# scripts/paper-tables.sh), which skip the runs they already hold (--resume):
# reports/ironing-2d/ (scripts/ironing-report.sh) and reports/crossed-tubes-3d/
# (scripts/crossed-tubes-report.sh).
# BENCH_LEVELS, BENCH_TIME_LIMIT (seconds per run, default 1800), BENCH_RESUME=1 (continue an
# interrupted sweep) and BENCH_OUT (another directory: reports/latest holds a sweep already,
# which is never deleted) adjust it.
set -euo pipefail
build=${1:-build}
default_out=reports/latest
levels=${BENCH_LEVELS:-0,1}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}

source "$(dirname "$0")/sweep-out-dir.sh"

scenes=$("$build/stiction" scenes | awk '{ print $1 }' |
  grep -vxF -e ironing-2d -e ironing-2d-frictionless -e crossed-tubes-3d -e block-strips -e block-strips-mr |
  paste -sd, -)
"$build/stiction" bench --scenes "$scenes" --levels "$levels" --time-limit "${BENCH_TIME_LIMIT:-1800}" --out "$out" \
  "${resume[@]}"

echo "bench: micro-benchmarks" >&2
{
  echo "# Micro-benchmarks, one core. Made by scripts/bench-all-scenes.sh at git $(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)"
  echo "# on $(nproc --all) cores, $(awk '/MemTotal/ {printf "%.1f GiB", $2/1048576}' /proc/meminfo), $(date -u '+%Y-%m-%d %H:%M UTC')."
  echo "# BLAS: $(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3)"
  "$build/benchmarks/bench_assembly" --benchmark_out="$out/assembly.json" --benchmark_out_format=json
  "$build/benchmarks/bench_backends" --benchmark_out="$out/backends.json" --benchmark_out_format=json
} > "$out/micro-benchmarks.txt" 2>/dev/null
echo "bench: wrote $out/report.md and $out/micro-benchmarks.txt" >&2
bash scripts/ironing-report.sh "$build"
bash scripts/crossed-tubes-report.sh "$build"
