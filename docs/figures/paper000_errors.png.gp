# pfgen simulate: estimation errors x - m of every filter against time.
# Data: /tmp/paper000.csv (pfgen results CSV; columns by position, header skipped).
set terminal pngcairo size 1000,680 noenhanced font 'Sans,10'
set output 'docs/figures/paper000_errors.png'
set datafile separator comma
set multiplot layout 2,1 title 'basin2006_quadratic: estimation errors x - m'
set grid
set key outside right top
set xlabel 't'
set lmargin 12
set rmargin 24
set xrange [0:9.2000000000000011]
set yrange [-10:10]
set ylabel 'x - m'
set title 'x: run 0 (clipped at +-10)'
plot '/tmp/paper000.csv' skip 1 using 1:5 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/paper000.csv' skip 1 using 1:8 with lines lw 1.5 lc rgb '#D55E00' title 'additive', \
     '/tmp/paper000.csv' skip 1 using 1:11 with lines lw 1.5 lc rgb '#009E73' title 'ekf-additive', \
     '/tmp/paper000.csv' skip 1 using 1:14 with lines lw 1.5 lc rgb '#CC79A7' title 'ekf', \
     '/tmp/paper000.csv' skip 1 using 1:17 with lines lw 1.5 lc rgb '#E69F00' title 'ekf-printed'
set title 'x: median over 200 runs, 5-95 % band (clipped at +-10)'
plot '/tmp/paper000.csv' skip 1 using 1:24:26 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/paper000.csv' skip 1 using 1:25 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/paper000.csv' skip 1 using 1:29:31 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/paper000.csv' skip 1 using 1:30 with lines lw 1.5 lc rgb '#D55E00' title 'additive', \
     '/tmp/paper000.csv' skip 1 using 1:34:36 with filledcurves fs transparent solid 0.2 noborder lc rgb '#009E73' notitle, \
     '/tmp/paper000.csv' skip 1 using 1:35 with lines lw 1.5 lc rgb '#009E73' title 'ekf-additive', \
     '/tmp/paper000.csv' skip 1 using 1:39:41 with filledcurves fs transparent solid 0.2 noborder lc rgb '#CC79A7' notitle, \
     '/tmp/paper000.csv' skip 1 using 1:40 with lines lw 1.5 lc rgb '#CC79A7' title 'ekf', \
     '/tmp/paper000.csv' skip 1 using 1:44:46 with filledcurves fs transparent solid 0.2 noborder lc rgb '#E69F00' notitle, \
     '/tmp/paper000.csv' skip 1 using 1:45 with lines lw 1.5 lc rgb '#E69F00' title 'ekf-printed'
unset multiplot
set output
