#!/usr/bin/env bash
# The crossed-tubes report (reports/crossed-tubes-3d/): crossed-tubes-3d through
# `stiction bench` (each run in its own process, rows kept as they finish), then, with
# gnuplot (installed here when missing), per run:
#   * <run>.svg: the total contact force (the multiplier's integral, on the upper tube)
#     against pseudo-time, and the Newton iterations per load increment;
#   * <run>-contact.png: the contact zone at the last completed step seen from above
#     (the deformed slave nodes facing the lower tube, within 24 mm of the symmetry
#     planes, in the x-z plane), coloured by the normal multiplier lambda_n (MPa) of the
#     tubes' pair ("crossing"; the upper tube's self-contact pair is left out), inactive
#     nodes in grey;
#   * summary.md: per run, the last step, its contact force (the paper's Figure 10: 26.77
#     on its mesh, 27.97 after two refinements) and the largest lambda_n.
# TUBES_LEVELS (default 0), TUBES_SOLVERS (default schur-amg) and TUBES_TIME_LIMIT
# (seconds per run, default 5400) adjust it.
set -euo pipefail
build=${1:-build}
out=${TUBES_OUT:-reports/crossed-tubes-3d}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
source "$(dirname "$0")/ensure-gnuplot.sh"
mkdir -p "$out"
"$build/stiction" bench --scenes crossed-tubes-3d --solvers "${TUBES_SOLVERS:-schur-amg}" \
  --levels "${TUBES_LEVELS:-0}" --time-limit "${TUBES_TIME_LIMIT:-5400}" --out "$out" --resume || true

summary="$out/summary.md"
# The note on the paper's unit that summary.md points to (reports/README.md) is now in
# reports/crossed-tubes-3d/README.md, Caveats.
{
  echo "# Crossed tubes: contact force and largest multiplier"
  echo
  echo "Made by \`scripts/crossed-tubes-report.sh\` from \`$out/runs/*/{steps,contact}.csv\`."
  echo "The paper (Fig. 10) prints the total contact force at t = 80: 26.77 on its mesh, 27.97 after two refinements (no unit; see reports/crossed-tubes-3d/README.md)."
  echo
  echo "| run | last step | t | contact force y (N) | largest lambda_n (MPa) | Newton iterations (all steps) |"
  echo "|---|---|---|---|---|---|"
} > "$summary"
for run in "$out"/runs/*/; do
  steps="$run/steps.csv" contact="$run/contact.csv"
  [ -f "$steps" ] && [ -f "$contact" ] || continue
  name=$(basename "$run")
  # t, contact force y, Newton iterations, converged.
  awk -F, '!/^#/ && !header { for (i = 1; i <= NF; i++) col[$i] = i; header = 1; next }
           !/^#/ { print $col["time"], $col["contact_crossing_force_y"], $col["newton_iterations"], $col["converged"] }' \
    "$steps" > "$out/$name.dat"
  # The last step's slave nodes: x, z, lambda_n, active (1) or not (0).
  last=$(awk -F, '!/^#/ && $1 ~ /^[0-9]+$/ { s = $1 } END { print s }' "$contact")
  # Only the part of the upper tube that faces the lower one: nodes at most 6 mm above the
  # highest node in contact (seen from above, the tube's upper wall would hide them).
  awk -F, -v s="$last" '!/^#/ && !header { for (i = 1; i <= NF; i++) col[$i] = i; header = 1; next }
           !/^#/ && $1 == s && $col["pair"] == "crossing" { n++; x[n] = $col["x"]; y[n] = $col["y"]; z[n] = $col["z"]; l[n] = $col["lambda_n"];
                              a[n] = ($col["state"] == "inactive" ? 0 : 1); if (a[n] && (!top_set || y[n] > top)) { top = y[n]; top_set = 1 } }
           END { for (i = 1; i <= n; i++) if (y[i] < top + 6) print x[i], z[i], l[i], a[i] }' \
    "$contact" > "$out/$name-contact.dat"
  read -r t force newton < <(awk '$4 == 1 { t = $1; f = $2 } { n += $3 } END { print t, f, n }' "$out/$name.dat")
  lmax=$(awk -F, -v s="$last" '!/^#/ && !header { for (i = 1; i <= NF; i++) col[$i] = i; header = 1; next }
               !/^#/ && $1 == s && $col["pair"] == "crossing" && $col["state"] != "inactive" && $col["lambda_n"] > m { m = $col["lambda_n"] }
               END { printf "%.2f", m }' "$contact")
  echo "| $name | $last | $t | $force | $lmax | $newton |" >> "$summary"
  gnuplot <<GNUPLOT
set terminal svg size 900,800 dynamic background '#ffffff'
set output '$out/$name.svg'
set multiplot layout 2,1 title '$name: total contact force (upper tube) and Newton iterations per increment'
set xlabel 'pseudo-time t (the upper ends lowered 0.5 t mm)'
set ylabel 'contact force y (N)'
plot '$out/$name.dat' using 1:(\$4 == 1 ? \$2 : 1/0) with linespoints pt 7 ps 0.4 notitle
set ylabel 'Newton iterations'
plot '$out/$name.dat' using 1:3 with impulses notitle
unset multiplot
set terminal pngcairo size 900,800 background '#ffffff'
set output '$out/$name-contact.png'
set title '$name: contact zone at step $last seen from above (lambda_n in MPa; grey: inactive)'
set xlabel 'x (mm, along the upper tube)'
set ylabel 'z (mm, along the lower tube)'
set size ratio -1
set xrange [0:24]
set yrange [0:24]
set key outside bottom center horizontal
set cblabel 'lambda_n (MPa)'
set palette rgbformulae 33,13,10
plot '$out/$name-contact.dat' using 1:(\$4 == 0 ? \$2 : 1/0) with points pt 7 ps 0.5 lc rgb '#c0c0c0' title 'inactive', \
     '' using 1:(\$4 == 1 ? \$2 : 1/0):3 with points pt 7 ps 1.0 palette title 'in contact'
GNUPLOT
done
echo "crossed-tubes-report: wrote $out" >&2
