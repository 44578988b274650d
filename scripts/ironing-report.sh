#!/usr/bin/env bash
# The shallow-ironing report (reports/ironing-2d/): ironing-2d and ironing-2d-frictionless
# through `stiction bench` (each run in its own process, rows kept as they finish), then,
# with gnuplot (installed when missing: scripts/ensure-gnuplot.sh), the force on the
# indenter against pseudo-time and the Newton iterations per load increment, one SVG per
# scene. The force on the indenter is the multiplier's integral (F3, contact_ironing_force_*:
# the force the slab exerts on the indenter); the published band at t = 1 (per unit
# thickness, with friction): vertical 268-332, horizontal 55-71.
# IRONING_LEVELS (default 0), IRONING_SOLVERS (default lu-mumps,schur-amg), IRONING_SCENES
# (default both) and IRONING_TIME_LIMIT (seconds per run, default 3600) adjust it.
set -euo pipefail
build=${1:-build}
out=${IRONING_OUT:-reports/ironing-2d}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
source "$(dirname "$0")/ensure-gnuplot.sh"
mkdir -p "$out"
"$build/stiction" bench --scenes "${IRONING_SCENES:-ironing-2d,ironing-2d-frictionless}" --solvers "${IRONING_SOLVERS:-lu-mumps,schur-amg}" \
  --levels "${IRONING_LEVELS:-0}" --time-limit "${IRONING_TIME_LIMIT:-3600}" --out "$out" --resume

# One data file per run: t, F3 x, F3 y, Newton iterations, converged (comments dropped).
plot_lines=()
for run in "$out"/runs/*/; do
  steps="$run/steps.csv"
  [ -f "$steps" ] || continue
  name=$(basename "$run")
  awk -F, '!/^#/ && !header { for (i = 1; i <= NF; i++) col[$i] = i; header = 1; next }
           !/^#/ { print $col["time"], $col["contact_ironing_force_x"], $col["contact_ironing_force_y"],
                   $col["newton_iterations"], $col["converged"] }' "$steps" > "$out/$name.dat"
done
for scene in ironing-2d ironing-2d-frictionless; do
  forces=() newton=()
  for dat in "$out"/"$scene"-L*.dat; do
    [ -f "$dat" ] || continue
    label=$(basename "$dat" .dat)
    forces+=("'$dat' using 1:(\$5 == 1 ? \$3 : 1/0) with lines title '$label F_y'"
             "'$dat' using 1:(\$5 == 1 ? -\$2 : 1/0) with lines title '$label -F_x'")
    newton+=("'$dat' using 1:4 with impulses title '$label'")
  done
  [ ${#forces[@]} -gt 0 ] || continue
  gnuplot <<GNUPLOT
set terminal svg size 900,900 dynamic background '#ffffff'
set output '$out/$scene.svg'
set multiplot layout 2,1 title '$scene: force of the slab on the indenter (F3) and Newton iterations per increment'
set xlabel 'pseudo-time t'
set ylabel 'force per unit thickness'
set key left top
set object 1 rectangle from 0.98,268 to 1.02,332 fillstyle empty border lc rgb 'red'
set object 2 rectangle from 0.98,55 to 1.02,71 fillstyle empty border lc rgb 'red'
set label 1 'published band at t = 1 (mu = 0.3)' at 1.03,300 textcolor rgb 'red'
plot $(IFS=,; echo "${forces[*]}")
unset object 1
unset object 2
unset label 1
set ylabel 'Newton iterations'
plot $(IFS=,; echo "${newton[*]}")
unset multiplot
GNUPLOT
done
echo "ironing-report: wrote $out" >&2
