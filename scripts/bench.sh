#!/usr/bin/env bash
# `make bench`: solve every built-in scene at mesh level 0 with lu-mumps, run the assembly
# micro-benchmarks (levels 0 and 1), and write reports/latest/ (report.md, per-scene
# steps.csv, assembly.json). The sweep harness of the solver-backend issue will replace
# the solve loop with `stiction bench`.
set -euo pipefail
build=${1:-build}
out=reports/latest
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
mkdir -p "$out"
report="$out/report.md"

{
  echo "# stiction benchmark report"
  echo
  echo "Made by \`make bench\` (scripts/bench.sh)."
  echo
  echo "- git revision: $(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD 2>/dev/null || echo ' (with uncommitted changes)')"
  echo "- PETSc: $(grep -m1 '^Version:' /usr/lib/petscdir/petsc*/x86_64-linux-gnu-real/lib/pkgconfig/PETSc.pc 2>/dev/null | cut -d' ' -f2 || echo unknown)"
  echo "- BLAS: $(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3) (OMP_NUM_THREADS=$OMP_NUM_THREADS OPENBLAS_NUM_THREADS=$OPENBLAS_NUM_THREADS)"
  echo "- machine: $(nproc --all) cores, $(awk '/MemTotal/ {printf "%.1f GiB", $2/1048576}' /proc/meminfo)"
  echo "- date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
  echo
  echo "## Built-in scenes, level 0, lu-mumps"
  echo
  echo "Per scene: \`stiction solve SCENE --level 0 --solver lu-mumps --out $out/SCENE\`; per-step figures in \`$out/SCENE/steps.csv\`."
  echo
  echo "| scene | unknowns | load steps | Newton its | assembly s | setup s | solve s | wall s |"
  echo "|---|---|---|---|---|---|---|---|"
} > "$report"

for scene in $("$build/stiction" scenes | awk '{print $1}'); do
  echo "bench: solving $scene" >&2
  /usr/bin/time -f "%e %M" -o "$out/$scene.time" "$build/stiction" solve "$scene" --level 0 --solver lu-mumps \
      --out "$out/$scene" --quiet
  awk -F, -v scene="$scene" '
    /^# mesh:/ { match($0, /total [0-9]+/); unknowns = substr($0, RSTART + 6, RLENGTH - 6) }
    /^[0-9]/ { steps++; its += $4; asm += $9; setup += $10; solve += $11; wall += $12 }
    END { printf "| %s | %s | %d | %d | %.2f | %.2f | %.2f | %.2f |\n", scene, unknowns, steps, its, asm, setup, solve, wall }
  ' "$out/$scene/steps.csv" >> "$report"
done

echo "bench: assembly micro-benchmarks" >&2
"$build/benchmarks/bench_assembly" --benchmark_out="$out/assembly.json" \
    --benchmark_out_format=json > "$out/assembly.txt"
{
  echo
  echo "## Assembly and SpMV (block-compression, P2 hierarchical, Neo-Hookean, one core)"
  echo
  echo "\`$build/benchmarks/bench_assembly\`; raw output in \`$out/assembly.txt\` and \`assembly.json\`."
  echo
  echo '```'
  grep -E "^(Benchmark|BM_)" "$out/assembly.txt"
  echo '```'
} >> "$report"
echo "bench: wrote $report" >&2
