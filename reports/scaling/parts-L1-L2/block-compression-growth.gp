# Redraw with: gnuplot block-compression-growth.gp (in this directory)
data = 'block-compression-growth.dat'
set terminal svg size 720,480 dynamic font 'sans,12'
set key left top
set grid
set logscale xy
set xlabel 'unknowns of the Newton system'
set output 'block-compression-time-per-solve.svg'
set ylabel 's / linear solve (set-up + Krylov)'
set title 'block-compression: time per linear solve'
plot data index 0 using 1:2 with linespoints pt 7 lw 2 title 'schur-amg (p = 1.13)'
set output 'block-compression-peak-memory.svg'
set ylabel 'peak resident memory (MB)'
set title 'block-compression: peak memory'
plot data index 0 using 1:3 with linespoints pt 7 lw 2 title 'schur-amg (p = 0.93)'
unset logscale
set xlabel 'mesh level'
set xtics 1
set ylabel 'Krylov iterations per Newton step'
set output 'block-compression-krylov.svg'
set title 'block-compression: Krylov iterations per Newton step'
plot data index 0 using 4:5 with linespoints pt 7 lw 2 title 'schur-amg'
