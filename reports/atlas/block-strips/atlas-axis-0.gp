# Redraw with: gnuplot atlas-axis-0.gp (in this directory)
set terminal svg size 650,340 dynamic font 'sans,12'
set output 'atlas-axis-0.svg'
set title "contact[0].friction_table" noenhanced
set xrange [-0.5:4.5]
set yrange [-0.5:2.5]
set xtics ('[[0.0; 0.0]; [4.0; 0.0]]' 0, '[[0.0; 0.0]; [4.0; 0.3]]' 1, '[[0.0; 0.0]; [4.0; 0.6]]' 2, '[[0.0; 0.0]; [4.0; 1.0]]' 3, '[[0.0; 0.0]; [4.0; 2.0]]' 4) noenhanced
set ytics ('schur-amg' 0, 'schur-gamg' 1, 'lu-mumps' 2) noenhanced
set cblabel 'Newton iterations'
set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')
set key below
plot 'atlas-axis-0.dat' index 0 using 1:2:3 with points pt 5 ps 5 lc palette title 'converged', \
     'atlas-axis-0.dat' index 1 using 1:2 with points pt 2 ps 4 lw 3 lc rgb 'black' title 'failed'
