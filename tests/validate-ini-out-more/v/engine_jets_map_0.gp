# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'engine_jets_map_0.png'
set title 'crossing jets, tau=200, t = 2, 45 x 45'
set grid
unset title
set multiplot layout 1,2 title 'crossing jets, tau=200, t = 2, 45 x 45'
set size ratio 1
set xrange [0:1]
set yrange [0:1]
set cbrange [0:3]
set palette rgb 33,13,10
set xlabel 'x'
set ylabel 'y'
set title 'Euler (upwind)'
plot 'engine_jets_map_0.dat' u 1:2:3 w image notitle
set title 'engine (NGP deposit)'
plot 'engine_jets_map_0.dat' u 1:2:4 w image notitle
unset multiplot
