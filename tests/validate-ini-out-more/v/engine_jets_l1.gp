# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'engine_jets_l1.png'
set title 'engine vs Euler: L1 distance / engine mass, 45 x 45'
set grid
set xlabel 't'
set ylabel 'L1 / mass'
plot 'engine_jets_l1.dat' u 1:2 w lp t 'rho, tau = 200', 'engine_jets_l1.dat' u 1:3 w l dt 2 t 'rho u, tau = 200', 'engine_jets_l1.dat' u 1:4 w lp t 'rho, tau = 1', 'engine_jets_l1.dat' u 1:5 w l dt 2 t 'rho u, tau = 1', 'engine_jets_l1.dat' u 1:6 w lp t 'rho, tau = 0.05, gas (1,1)', 'engine_jets_l1.dat' u 1:7 w l dt 2 t 'rho u, tau = 0.05'
