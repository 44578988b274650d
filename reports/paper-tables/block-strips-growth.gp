# Redraw with: gnuplot block-strips-growth.gp (in this directory)
data = 'block-strips-growth.dat'
set terminal svg size 720,480 dynamic font 'sans,12'
set key left top
set grid
set logscale xy
set xlabel 'unknowns of the Newton system'
set output 'block-strips-time-per-solve.svg'
set ylabel 's / linear solve (set-up + Krylov)'
set title 'block-strips: time per linear solve (recorded sample)'
plot data index 0 using 1:2 with linespoints pt 7 lw 2 title 'fieldsplit-schur (p = 1.40)', \
     data index 1 using 1:2 with linespoints pt 7 lw 2 title 'lu-mumps (p = 1.56)', \
     data index 2 using 1:2 with linespoints pt 7 lw 2 title 'lu-mumps-blr (p = 1.33)', \
     data index 3 using 1:2 with linespoints pt 7 lw 2 title 'schur-amg (p = 1.24)', \
     data index 4 using 1:2 with linespoints pt 7 lw 2 title 'schur-gamg (p = 1.20)', \
     data index 5 using 1:2 with linespoints pt 7 lw 2 title 'schur-lu (p = 1.13)', \
     data index 6 using 1:2 with points pt 6 ps 1.5 lw 2 title 'paper GlobalLU', \
     data index 7 using 1:2 with points pt 6 ps 1.5 lw 2 title 'paper SchurMHP'
set output 'block-strips-peak-memory.svg'
set ylabel 'peak resident memory (MB)'
set title 'block-strips: peak memory (recorded sample)'
plot data index 0 using 1:3 with linespoints pt 7 lw 2 title 'fieldsplit-schur (p = 0.85)', \
     data index 1 using 1:3 with linespoints pt 7 lw 2 title 'lu-mumps (p = 1.29)', \
     data index 2 using 1:3 with linespoints pt 7 lw 2 title 'lu-mumps-blr (p = 1.15)', \
     data index 3 using 1:3 with linespoints pt 7 lw 2 title 'schur-amg (p = 0.73)', \
     data index 4 using 1:3 with linespoints pt 7 lw 2 title 'schur-gamg (p = 0.72)', \
     data index 5 using 1:3 with linespoints pt 7 lw 2 title 'schur-lu (p = 0.81)', \
     data index 6 using 1:3 with points pt 6 ps 1.5 lw 2 title 'paper GlobalLU', \
     data index 7 using 1:3 with points pt 6 ps 1.5 lw 2 title 'paper SchurMHP'
unset logscale
set xlabel 'mesh level'
set xtics 1
set ylabel 'Krylov iterations per Newton step'
set output 'block-strips-krylov.svg'
set title 'block-strips: Krylov iterations per Newton step (recorded sample)'
plot data index 0 using 4:5 with linespoints pt 7 lw 2 title 'fieldsplit-schur', \
     data index 1 using 4:5 with linespoints pt 7 lw 2 title 'lu-mumps', \
     data index 2 using 4:5 with linespoints pt 7 lw 2 title 'lu-mumps-blr', \
     data index 3 using 4:5 with linespoints pt 7 lw 2 title 'schur-amg', \
     data index 4 using 4:5 with linespoints pt 7 lw 2 title 'schur-gamg', \
     data index 5 using 4:5 with linespoints pt 7 lw 2 title 'schur-lu'
