# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'V8_agglo-constant_M0.png'
set title 'Constant kernel: M0(t)/N0, engine vs CVODE'
set grid
set xlabel 't K_{11} N_0 / 2'
set ylabel 'M_0/N_0'
set logscale y
plot 'V8_agglo-constant_M0.dat' u 1:2:3:4 w yerrorbars pt 7 t 'engine', 'V8_agglo-constant_M0.dat' u 1:5 w l t 'CVODE'

