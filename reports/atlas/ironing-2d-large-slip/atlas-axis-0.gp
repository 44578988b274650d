# Redraw with: gnuplot atlas-axis-0.gp (in this directory)
set terminal svg size 650,400 dynamic font 'sans,12'
set output 'atlas-axis-0.svg'
set title "load.phases" noenhanced
set xrange [-0.5:4.5]
set yrange [-0.5:3.5]
set xtics ('[{until = 1.0; steps = 10}; {until = 2.0; steps = 200}]' 0, '[{until = 1.0; steps = 10}; {until = 2.0; steps = 50}]' 1, '[{until = 1.0; steps = 10}; {until = 2.0; steps = 20}]' 2, '[{until = 1.0; steps = 10}; {until = 2.0; steps = 10}]' 3, '[{until = 1.0; steps = 10}; {until = 2.0; steps = 5}]' 4) noenhanced
set ytics ('schur-amg' 0, 'schur-gamg' 1, 'fieldsplit-schur' 2, 'lu-mumps' 3) noenhanced
set cblabel 'Newton iterations'
set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')
set key below
plot 'atlas-axis-0.dat' index 0 using 1:2:3 with points pt 5 ps 5 lc palette title 'converged', \
     'atlas-axis-0.dat' index 1 using 1:2 with points pt 2 ps 4 lw 3 lc rgb 'black' title 'failed'
