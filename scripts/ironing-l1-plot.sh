#!/usr/bin/env bash
# Plots the level-1 runs kept in reports/ironing-2d-L1 (force on the indenter against
# pseudo-time, converged increments only) beside the level-0 lu-mumps runs of
# reports/ironing-2d, with gnuplot. Every <backend>-<frictional|frictionless>-steps.csv
# there is one run of `stiction solve <scene> --level 1 --solver <backend>`; the script
# plots what is kept and runs nothing.
# Usage (from the repository root): bash scripts/ironing-l1-plot.sh
set -euo pipefail
here=reports/ironing-2d-L1
source scripts/ensure-gnuplot.sh
fy=() fx=()
for steps in "$here"/*-steps.csv; do
  name=$(basename "$steps" -steps.csv)  # e.g. lu-mumps-frictional
  # t, F3 x, F3 y of every converged increment, in time order (restarts may overlap).
  awk -F, '!/^#/ && /^step,/ { for (i = 1; i <= NF; i++) col[$i] = i; next }
    !/^#/ && $col["converged"] == 1 { print $col["time"], $col["contact_ironing_force_x"], $col["contact_ironing_force_y"] }' \
    "$steps" | sort -g -k1,1 -u > "$here/$name-L1.dat"
  fy+=("'$here/$name-L1.dat' using 1:3 with lines lw 2 title '$name, level 1'")
  fx+=("'$here/$name-L1.dat' using 1:2 with lines lw 2 title '$name, level 1'")
done
for scene in ironing-2d ironing-2d-frictionless; do
  dat=reports/ironing-2d/$scene-L0-lu-mumps.dat
  [ -f "$dat" ] || continue
  fy+=("'$dat' using 1:(\$5 == 1 ? \$3 : 1/0) with lines dt 2 title '$scene lu-mumps, level 0'")
  fx+=("'$dat' using 1:(\$5 == 1 ? \$2 : 1/0) with lines dt 2 title '$scene lu-mumps, level 0'")
done
join() { local IFS=,; echo "$*"; }
gnuplot <<GNUPLOT
set terminal svg size 900,800 dynamic background '#ffffff'
set output '$here/ironing-2d-L1.svg'
set multiplot layout 2,1 title 'ironing-2d: force of the slab on the indenter (F3) at level 1 against level 0'
set xlabel 'pseudo-time t'
set ylabel 'F_y (per unit thickness)'
set key bottom right
plot $(join "${fy[@]}")
set ylabel 'F_x (per unit thickness)'
plot $(join "${fx[@]}")
unset multiplot
GNUPLOT
