# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'V12_H.png'
set title 'V12: long-time kernel H(Kn_D) of the Langevin detector (95% intervals)'
set grid
set logscale xy
set xlabel 'Kn_D'
set ylabel 'H = K m_red / (f_red R^3)'
set key left
plot 'V12_H.dat' u 1:2:3:4 w yerrorbars pt 7 t 'langevin', 'V12_H.dat' u 1:5 w l t 'Gopalakrishnan & Hogan', 'V12_H.dat' u 1:6 w l t 'Dahneke', 'V12_H.dat' u 1:7 w l dt 2 t 'continuum', 'V12_H.dat' u 1:8 w l dt 3 t 'free molecular'
