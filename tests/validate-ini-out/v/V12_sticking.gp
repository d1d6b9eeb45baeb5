# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'V12_sticking.png'
set title 'V12: DLVO sticking fraction at first contact versus barrier height'
set grid
set logscale y
set xlabel 'W_max / k_B T'
set ylabel 'sticking fraction'
plot 'V12_sticking.dat' u ($6==0.05?$1:1/0):2 w p pt 7 t 'langevin, Kn_D 0.05', 'V12_sticking.dat' u ($6==0.05?$1:1/0):3 w l t 'contact time, Kn_D 0.05', 'V12_sticking.dat' u ($6==0.5?$1:1/0):2 w p pt 5 t 'langevin, Kn_D 0.5', 'V12_sticking.dat' u ($6==0.5?$1:1/0):3 w l t 'contact time, Kn_D 0.5', 'V12_sticking.dat' u 1:4 w l dt 2 t 'exp(-W/kT) (flux-weighted)', 'V12_sticking.dat' u 1:5 w l dt 3 t 'erfc(sqrt(W/kT)) (stationary)'
