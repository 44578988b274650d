# Redraw with: gnuplot atlas-axis-0.gp (in this directory)
set terminal svg size 740,400 dynamic font 'sans,12'
set output 'atlas-axis-0.svg'
set title "material[0].kappa" noenhanced
set xrange [-0.5:5.5]
set yrange [-0.5:3.5]
set xtics ('10' 0, '100' 1, '1000' 2, '10000' 3, '100000' 4, '1000000' 5) noenhanced
set ytics ('schur-amg' 0, 'schur-gamg' 1, 'gamg' 2, 'lu-mumps' 3) noenhanced
set cblabel 'Newton iterations'
set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')
set key below
plot 'atlas-axis-0.dat' index 0 using 1:2:3 with points pt 5 ps 5 lc palette title 'converged', \
     'atlas-axis-0.dat' index 1 using 1:2 with points pt 2 ps 4 lw 3 lc rgb 'black' title 'failed'
