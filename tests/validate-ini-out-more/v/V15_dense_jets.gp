# gnuplot script written by smolbridge validate; run it in this directory.
set terminal pngcairo size 960,640 noenhanced
set output 'V15_dense_jets.png'
set title 'V15: exit mass profiles of the crossing jets, east side (0-1, bottom to top) then north side (1-2, east to west)'
set grid
set xlabel 's (east side y/L, then north side 2 - x/L)'
set ylabel 'exit mass density (normalised)'
set key top left
plot 'V15_dense_jets.dat' u 1:2 w steps t 'no collision, west jet', '' u 1:3 w steps t 'no collision, south jet', '' u 1:4 w steps t 'phi 0.02, west', '' u 1:5 w steps t 'phi 0.02, south', '' u 1:6 w steps t 'phi 0.2, west', '' u 1:7 w steps t 'phi 0.2, south', '' u 1:8 w l lw 2 t 'Euler (pressureless)'
