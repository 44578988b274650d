# Redraw with: gnuplot tradeoff.gp (in this directory)
data = 'tradeoff.dat'
set terminal svg size 720,480 dynamic font 'sans,12'
set output 'tradeoff.svg'
set key right top
set grid
set logscale xy
set xlabel 'wall time of the run (s)'
set ylabel 'displacement error against the reference (H1, relative)'
set title 'speed against accuracy'
plot data index 0 using 1:2 with points pt 7 ps 1.2 title 'ilu-gmres', \
     data index 1 using 1:2 with points pt 7 ps 1.2 title 'lu-mumps-blr', \
     data index 2 using 1:2 with points pt 7 ps 1.2 title 'schur-amg', \
     data index 3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front'
