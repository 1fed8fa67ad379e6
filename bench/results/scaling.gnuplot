set datafile separator ','
set terminal pngcairo size 1200,480 noenhanced font ',11'
set output '/work/main/bench/results/scaling.png'
set multiplot layout 1,2 title 'tumbling hollow sphere, energy_momentum, h = 0.01 (2 shared cores)'
set logscale xy
set grid
set xlabel 'elements (hex8)'
set key inside top left box opaque
set title 'seconds per step'
set ylabel 's/step'
plot '/work/main/bench/results/scaling.csv' using 3:8 with linespoints lw 2 lc rgb '#d62728' pt 7 title 'UMFPACK (direct)', '/work/main/bench/results/scaling.csv' using 3:($8*$10) with linespoints lw 2 lc rgb '#d62728' dt 2 pt 6 title '  its linear solver', '/work/main/bench/results/scaling_petsc_gamg.csv' using 3:8 with linespoints lw 2 lc rgb '#1f77b4' pt 7 title 'PETSc GMRES + GAMG (petsc_gamg)', '/work/main/bench/results/scaling_petsc_gamg.csv' using 3:($8*$10) with linespoints lw 2 lc rgb '#1f77b4' dt 2 pt 6 title '  its linear solver'
set title 'peak resident memory'
set ylabel 'MB'
plot '/work/main/bench/results/scaling.csv' using 3:14 with linespoints lw 2 lc rgb '#d62728' pt 7 title 'UMFPACK (direct)', '/work/main/bench/results/scaling_petsc_gamg.csv' using 3:14 with linespoints lw 2 lc rgb '#1f77b4' pt 7 title 'PETSc GMRES + GAMG (petsc_gamg)'
unset multiplot
