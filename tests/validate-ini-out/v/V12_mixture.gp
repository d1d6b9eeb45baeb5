# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'V12_mixture.png'
set title 'V12: 20 nm + 200 nm, K_e/K_GH per pair type (95% intervals)'
set grid
set xrange [-0.5:2.5]
set xtics ('20-20' 0, '20-200' 1, '200-200' 2)
set ylabel 'K_e / K_GH'
plot 'V12_mixture.dat' u 1:3:4:5 w yerrorbars pt 7 t 'langevin', 1 lc rgb 'black' t ''
