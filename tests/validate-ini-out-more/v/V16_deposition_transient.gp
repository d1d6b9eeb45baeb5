# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'V16_deposition_transient.png'
set title 'V16: deposition flux / n sqrt(D/(pi t)) (two walls)'
set grid
set logscale x
set xlabel 't D / W^2'
set ylabel 'flux / (n sqrt(D/(pi t)))'
plot 'V16_deposition_transient.dat' u 1:2 w lp t 'bridge', 'V16_deposition_transient.dat' u 1:3 w l t 'exact (slab)', 'V16_deposition_transient.dat' u 1:4 w lp t 'chord only', 1 lc rgb 'black' t 'semi-infinite'
