# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'V8_agglo-constant_nk.png'
set title 'Constant kernel: engine n_k (99.9% intervals) vs CVODE'
set grid
set logscale y
set xlabel 'cluster size k'
set ylabel 'n_k / N_0'
set key outside
plot for [c=0:3] 'V8_agglo-constant_nk.dat' u 1:(column(2+4*c)):(column(3+4*c)):(column(4+4*c)) w yerrorbars pt 7 lc c+1 t sprintf('engine t = %s t_{1/2}',word('0.5 1 2 5',c+1)), for [c=0:3] 'V8_agglo-constant_nk.dat' u 1:(column(5+4*c)) w l lc c+1 t sprintf('CVODE t = %s t_{1/2}',word('0.5 1 2 5',c+1))

