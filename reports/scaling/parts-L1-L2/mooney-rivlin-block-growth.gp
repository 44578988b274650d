# Redraw with: gnuplot mooney-rivlin-block-growth.gp (in this directory)
data = 'mooney-rivlin-block-growth.dat'
set terminal svg size 720,480 dynamic font 'sans,12'
set key left top
set grid
set logscale xy
set xlabel 'unknowns of the Newton system'
set output 'mooney-rivlin-block-time-per-solve.svg'
set ylabel 's / linear solve (set-up + Krylov)'
set title 'mooney-rivlin-block: time per linear solve'
plot data index 0 using 1:2 with linespoints pt 7 lw 2 title 'schur-amg (p = 1.08)'
set output 'mooney-rivlin-block-peak-memory.svg'
set ylabel 'peak resident memory (MB)'
set title 'mooney-rivlin-block: peak memory'
plot data index 0 using 1:3 with linespoints pt 7 lw 2 title 'schur-amg (p = 0.95)'
unset logscale
set xlabel 'mesh level'
set xtics 1
set ylabel 'Krylov iterations per Newton step'
set output 'mooney-rivlin-block-krylov.svg'
set title 'mooney-rivlin-block: Krylov iterations per Newton step'
plot data index 0 using 4:5 with linespoints pt 7 lw 2 title 'schur-amg'
