# Redraw with: gnuplot atlas-axis-1.gp (in this directory)
set terminal svg size 560,340 dynamic font 'sans,12'
set output 'atlas-axis-1.svg'
set title "load.phases" noenhanced
set xrange [-0.5:3.5]
set yrange [-0.5:2.5]
set xtics ('[{until = 4.0; steps = 4}; {until = 8.0; steps = 8}]' 0, '[{until = 4.0; steps = 4}; {until = 8.0; steps = 4}]' 1, '[{until = 4.0; steps = 4}; {until = 8.0; steps = 2}]' 2, '[{until = 4.0; steps = 4}; {until = 8.0; steps = 1}]' 3) noenhanced
set ytics ('schur-amg' 0, 'schur-gamg' 1, 'lu-mumps' 2) noenhanced
set cblabel 'Newton iterations'
set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')
set key below
plot 'atlas-axis-1.dat' index 0 using 1:2:3 with points pt 5 ps 5 lc palette title 'converged', \
     'atlas-axis-1.dat' index 1 using 1:2 with points pt 2 ps 4 lw 3 lc rgb 'black' title 'failed'
