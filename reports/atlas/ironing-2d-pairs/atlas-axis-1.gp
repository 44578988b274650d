# Redraw with: gnuplot atlas-axis-1.gp (in this directory)
set terminal svg size 470,340 dynamic font 'sans,12'
set output 'atlas-axis-1.svg'
set title "schur-gamg: material[1].E & contact[0].friction" noenhanced
set xrange [-0.5:2.5]
set yrange [-0.5:2.5]
set xtics ('68960' 0, '689600' 1, '6896000' 2) noenhanced
set ytics ('0' 0, '0.3' 1, '1' 2) noenhanced
set cblabel 'Newton iterations'
set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')
set key below
plot 'atlas-axis-1.dat' index 0 using 1:2:3 with points pt 5 ps 5 lc palette title 'converged', \
     'atlas-axis-1.dat' index 1 using 1:2 with points pt 2 ps 4 lw 3 lc rgb 'black' title 'failed'
