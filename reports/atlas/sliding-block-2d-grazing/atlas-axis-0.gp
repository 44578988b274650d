# Redraw with: gnuplot atlas-axis-0.gp (in this directory)
set terminal svg size 920,400 dynamic font 'sans,12'
set output 'atlas-axis-0.svg'
set title "dirichlet[0].value" noenhanced
set xrange [-0.5:7.5]
set yrange [-0.5:3.5]
set xtics ('[-1e-2]' 0, '[-1e-6]' 1, '[-1e-9]' 2, '[-1e-12]' 3, '[0.0]' 4, '[1e-12]' 5, '[1e-9]' 6, '[1e-6]' 7) noenhanced
set ytics ('schur-amg' 0, 'schur-gamg' 1, 'fieldsplit-schur' 2, 'lu-mumps' 3) noenhanced
set cblabel 'Newton iterations'
set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')
set key below
plot 'atlas-axis-0.dat' index 0 using 1:2:3 with points pt 5 ps 5 lc palette title 'converged', \
     'atlas-axis-0.dat' index 1 using 1:2 with points pt 2 ps 4 lw 3 lc rgb 'black' title 'failed'
