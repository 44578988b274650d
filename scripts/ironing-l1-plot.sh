#!/usr/bin/env bash
# Plots the level-1 runs kept in reports/ironing-2d-L1 (force on the indenter against
# pseudo-time, converged increments only) beside the level-0 lu-mumps runs of
# reports/ironing-2d, with gnuplot. Those runs were pieced from restarts, so unlike
# scripts/ironing-report.sh it plots the kept CSV parts and runs nothing.
# Usage (from the repository root): bash scripts/ironing-l1-plot.sh
set -euo pipefail
here=reports/ironing-2d-L1
source scripts/ensure-gnuplot.sh
for scene in frictional frictionless; do
  # t, F3 x, F3 y of every converged increment, in time order (the parts overlap at restarts).
  cat "$here/$scene"-part*-steps.csv | awk -F, '!/^#/ && /^step,/ { for (i = 1; i <= NF; i++) col[$i] = i; next }
    !/^#/ && $col["converged"] == 1 { print $col["time"], $col["contact_ironing_force_x"], $col["contact_ironing_force_y"] }' |
    sort -g -k1,1 -u > "$here/$scene-L1.dat"
done
gnuplot <<GNUPLOT
set terminal svg size 900,800 dynamic background '#ffffff'
set output '$here/ironing-2d-L1.svg'
set multiplot layout 2,1 title 'ironing-2d: force of the slab on the indenter (F3), schur-amg at level 1 against lu-mumps at level 0'
set xlabel 'pseudo-time t'
set ylabel 'F_y (per unit thickness)'
set key bottom right
plot '$here/frictional-L1.dat' using 1:3 with lines lw 2 title 'mu = 0.3, level 1', \
     'reports/ironing-2d/ironing-2d-L0-lu-mumps.dat' using 1:(\$5 == 1 ? \$3 : 1/0) with lines dt 2 title 'mu = 0.3, level 0', \
     '$here/frictionless-L1.dat' using 1:3 with lines lw 2 title 'frictionless, level 1', \
     'reports/ironing-2d/ironing-2d-frictionless-L0-lu-mumps.dat' using 1:(\$5 == 1 ? \$3 : 1/0) with lines dt 2 title 'frictionless, level 0'
set ylabel 'F_x (per unit thickness)'
plot '$here/frictional-L1.dat' using 1:2 with lines lw 2 title 'mu = 0.3, level 1', \
     'reports/ironing-2d/ironing-2d-L0-lu-mumps.dat' using 1:(\$5 == 1 ? \$2 : 1/0) with lines dt 2 title 'mu = 0.3, level 0', \
     '$here/frictionless-L1.dat' using 1:2 with lines lw 2 title 'frictionless, level 1', \
     'reports/ironing-2d/ironing-2d-frictionless-L0-lu-mumps.dat' using 1:(\$5 == 1 ? \$2 : 1/0) with lines dt 2 title 'frictionless, level 0'
unset multiplot
GNUPLOT
