#!/usr/bin/env bash
# Plots the runs kept in reports/ironing-2d-L<level> (force on the indenter against
# pseudo-time, converged increments only) beside the lu-mumps runs of the level below
# (reports/ironing-2d for level 0), with gnuplot. Every <backend>-<frictional|frictionless>-steps.csv
# there is one run of `stiction solve <scene> --level <level> --solver <backend>` (its rows
# may come from several restarts); the script plots what is kept and runs nothing.
# Usage (from the repository root): bash scripts/ironing-level-plot.sh 1|2
set -euo pipefail
level=${1:?usage: ironing-level-plot.sh LEVEL (1 or 2)}
here=reports/ironing-2d-L$level
[ -d "$here" ] || { echo "ironing-level-plot.sh: no $here" >&2; exit 1; }
source scripts/ensure-gnuplot.sh
# t, F3 x, F3 y of every converged increment of steps.csv $1, in time order (restarts may overlap).
forces() {
  awk -F, '!/^#/ && /^step,/ { for (i = 1; i <= NF; i++) col[$i] = i; next }
    !/^#/ && $col["converged"] == 1 { print $col["time"], $col["contact_ironing_force_x"], $col["contact_ironing_force_y"] }' \
    "$1" | sort -g -k1,1 -u
}
fy=() fx=()
for steps in "$here"/*-steps.csv; do
  name=$(basename "$steps" -steps.csv)  # e.g. lu-mumps-frictional
  forces "$steps" > "$here/$name-L$level.dat"
  fy+=("'$here/$name-L$level.dat' using 1:3 with lines lw 2 title '$name, level $level'")
  fx+=("'$here/$name-L$level.dat' using 1:2 with lines lw 2 title '$name, level $level'")
done
below=$((level - 1))
if [ "$below" -eq 0 ]; then
  for scene in ironing-2d ironing-2d-frictionless; do
    dat=reports/ironing-2d/$scene-L0-lu-mumps.dat
    [ -f "$dat" ] || continue
    fy+=("'$dat' using 1:(\$5 == 1 ? \$3 : 1/0) with lines dt 2 title '$scene lu-mumps, level 0'")
    fx+=("'$dat' using 1:(\$5 == 1 ? \$2 : 1/0) with lines dt 2 title '$scene lu-mumps, level 0'")
  done
else
  for dat in reports/ironing-2d-L$below/lu-mumps-*-L$below.dat; do
    [ -f "$dat" ] || continue
    name=$(basename "$dat" -L$below.dat)
    fy+=("'$dat' using 1:3 with lines dt 2 title '$name, level $below'")
    fx+=("'$dat' using 1:2 with lines dt 2 title '$name, level $below'")
  done
fi
join() { local IFS=,; echo "$*"; }
gnuplot <<GNUPLOT
set terminal svg size 900,800 dynamic background '#ffffff'
set output '$here/ironing-2d-L$level.svg'
set multiplot layout 2,1 title 'ironing-2d: force of the slab on the indenter (F3) at level $level against level $below'
set xlabel 'pseudo-time t'
set ylabel 'F_y (per unit thickness)'
set key bottom right
plot $(join "${fy[@]}")
set ylabel 'F_x (per unit thickness)'
plot $(join "${fx[@]}")
unset multiplot
GNUPLOT
