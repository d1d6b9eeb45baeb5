# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'V12_flat_Kn0.5.png'
set title 'V12: K_e / K_ref versus dt/tau_p, Kn_D = 0.5 (95% intervals)'
set grid
set logscale x
set xrange [0.005:2000]
set xlabel 'dt / tau_p'
set ylabel 'K_e / K_ref (contact time, dt = 0.01 tau_p)'
set key outside
k = 0.5
plot for [d=0:4] 'V12_flat_Kn0.5.dat' u ($1==k && $3==d ? $2 : 1/0):4:5:6 w yerrorlines t word('langevin contact-time overlap bessel3 exact-bb3', d+1), 1 lc rgb 'black' t ''
