# Redraw with: gnuplot atlas-axis-1.gp (in this directory)
set terminal svg size 650,400 dynamic font 'sans,12'
set output 'atlas-axis-1.svg'
set title "material[1].E" noenhanced
set xrange [-0.5:4.5]
set yrange [-0.5:3.5]
set xtics ('689.6' 0, '6896' 1, '68960' 2, '689600' 3, '6896000' 4) noenhanced
set ytics ('schur-amg' 0, 'schur-gamg' 1, 'fieldsplit-schur' 2, 'lu-mumps' 3) noenhanced
set cblabel 'Newton iterations'
set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')
set key below
plot 'atlas-axis-1.dat' index 0 using 1:2:3 with points pt 5 ps 5 lc palette title 'converged', \
     'atlas-axis-1.dat' index 1 using 1:2 with points pt 2 ps 4 lw 3 lc rgb 'black' title 'failed'
