# Redraw with: gnuplot block-strips-mr-growth.gp (in this directory)
data = 'block-strips-mr-growth.dat'
set terminal svg size 720,480 dynamic font 'sans,12'
set key left top
set grid
set logscale xy
set xlabel 'unknowns of the Newton system'
set output 'block-strips-mr-time-per-solve.svg'
set ylabel 's / linear solve (set-up + Krylov)'
set title 'block-strips-mr: time per linear solve (recorded sample)'
plot data index 0 using 1:2 with linespoints pt 7 lw 2 title 'fieldsplit-schur (p = 1.42)', \
     data index 1 using 1:2 with linespoints pt 7 lw 2 title 'ilu-gmres (p = 2.43)', \
     data index 2 using 1:2 with linespoints pt 7 lw 2 title 'lu-mumps (p = 1.55)', \
     data index 3 using 1:2 with linespoints pt 7 lw 2 title 'lu-mumps-blr (p = 1.34)', \
     data index 4 using 1:2 with linespoints pt 7 lw 2 title 'schur-amg (p = 1.15)', \
     data index 5 using 1:2 with linespoints pt 7 lw 2 title 'schur-gamg (p = 1.12)', \
     data index 6 using 1:2 with linespoints pt 7 lw 2 title 'schur-lu (p = 1.96)', \
     data index 7 using 1:2 with points pt 6 ps 1.5 lw 2 title 'paper GlobalLU', \
     data index 8 using 1:2 with points pt 6 ps 1.5 lw 2 title 'paper SchurHP'
set output 'block-strips-mr-peak-memory.svg'
set ylabel 'peak resident memory (MB)'
set title 'block-strips-mr: peak memory (recorded sample)'
plot data index 0 using 1:3 with linespoints pt 7 lw 2 title 'fieldsplit-schur (p = 0.97)', \
     data index 1 using 1:3 with linespoints pt 7 lw 2 title 'ilu-gmres (p = 0.94)', \
     data index 2 using 1:3 with linespoints pt 7 lw 2 title 'lu-mumps (p = 1.28)', \
     data index 3 using 1:3 with linespoints pt 7 lw 2 title 'lu-mumps-blr (p = 1.16)', \
     data index 4 using 1:3 with linespoints pt 7 lw 2 title 'schur-amg (p = 0.75)', \
     data index 5 using 1:3 with linespoints pt 7 lw 2 title 'schur-gamg (p = 0.75)', \
     data index 6 using 1:3 with linespoints pt 7 lw 2 title 'schur-lu (p = 0.92)', \
     data index 7 using 1:3 with points pt 6 ps 1.5 lw 2 title 'paper GlobalLU', \
     data index 8 using 1:3 with points pt 6 ps 1.5 lw 2 title 'paper SchurHP'
unset logscale
set xlabel 'mesh level'
set xtics 1
set ylabel 'Krylov iterations per Newton step'
set output 'block-strips-mr-krylov.svg'
set title 'block-strips-mr: Krylov iterations per Newton step (recorded sample)'
plot data index 0 using 4:5 with linespoints pt 7 lw 2 title 'fieldsplit-schur', \
     data index 1 using 4:5 with linespoints pt 7 lw 2 title 'ilu-gmres', \
     data index 2 using 4:5 with linespoints pt 7 lw 2 title 'lu-mumps', \
     data index 3 using 4:5 with linespoints pt 7 lw 2 title 'lu-mumps-blr', \
     data index 4 using 4:5 with linespoints pt 7 lw 2 title 'schur-amg', \
     data index 5 using 4:5 with linespoints pt 7 lw 2 title 'schur-gamg', \
     data index 6 using 4:5 with linespoints pt 7 lw 2 title 'schur-lu'
