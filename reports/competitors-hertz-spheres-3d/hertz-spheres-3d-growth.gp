# Redraw with: gnuplot hertz-spheres-3d-growth.gp (in this directory)
data = 'hertz-spheres-3d-growth.dat'
set terminal svg size 720,480 dynamic font 'sans,12'
set key left top
set grid
set logscale xy
set xlabel 'unknowns of the Newton system'
set output 'hertz-spheres-3d-time-per-solve.svg'
set ylabel 's / linear solve (set-up + Krylov)'
set title 'hertz-spheres-3d: time per linear solve'
plot data index 0 using 1:2 with linespoints pt 7 lw 2 title 'fieldsplit-schur (p = 1.65)', \
     data index 1 using 1:2 with linespoints pt 7 lw 2 title 'lu-mumps (p = 1.78)', \
     data index 2 using 1:2 with linespoints pt 7 lw 2 title 'lu-mumps-blr (p = 1.59)', \
     data index 3 using 1:2 with linespoints pt 7 lw 2 title 'schur-amg (p = 1.52)', \
     data index 4 using 1:2 with linespoints pt 7 lw 2 title 'schur-gamg (p = 1.54)'
set output 'hertz-spheres-3d-peak-memory.svg'
set ylabel 'peak resident memory (MB)'
set title 'hertz-spheres-3d: peak memory'
plot data index 0 using 1:3 with linespoints pt 7 lw 2 title 'fieldsplit-schur (p = 0.73)', \
     data index 1 using 1:3 with linespoints pt 7 lw 2 title 'lu-mumps (p = 1.14)', \
     data index 2 using 1:3 with linespoints pt 7 lw 2 title 'lu-mumps-blr (p = 1.05)', \
     data index 3 using 1:3 with linespoints pt 7 lw 2 title 'schur-amg (p = 0.60)', \
     data index 4 using 1:3 with linespoints pt 7 lw 2 title 'schur-gamg (p = 0.61)'
unset logscale
set xlabel 'mesh level'
set xtics 1
set ylabel 'Krylov iterations per Newton step'
set output 'hertz-spheres-3d-krylov.svg'
set title 'hertz-spheres-3d: Krylov iterations per Newton step'
plot data index 0 using 4:5 with linespoints pt 7 lw 2 title 'fieldsplit-schur', \
     data index 1 using 4:5 with linespoints pt 7 lw 2 title 'lu-mumps', \
     data index 2 using 4:5 with linespoints pt 7 lw 2 title 'lu-mumps-blr', \
     data index 3 using 4:5 with linespoints pt 7 lw 2 title 'schur-amg', \
     data index 4 using 4:5 with linespoints pt 7 lw 2 title 'schur-gamg'
