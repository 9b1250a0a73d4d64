# pfgen simulate: estimation errors x - m of every filter against time.
# Data: /tmp/paper001.csv (pfgen results CSV; columns by position, header skipped).
set terminal pngcairo size 1000,1320 noenhanced font 'Sans,10'
set output 'docs/figures/paper001_errors.png'
set datafile separator comma
set multiplot layout 4,1 title 'basin_skliar_partial: estimation errors x - m'
set grid
set key outside right top
set xlabel 't'
set lmargin 12
set rmargin 24
set xrange [0:6.5]
set yrange [-10:10]
set ylabel 'x1 - m'
set title 'x1: run 0 (clipped at +-10)'
plot '/tmp/paper001.csv' skip 1 using 1:8 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/paper001.csv' skip 1 using 1:14 with lines lw 1.5 lc rgb '#D55E00' title 'ekf', \
     '/tmp/paper001.csv' skip 1 using 1:20 with lines lw 1.5 lc rgb '#009E73' title 'ekf-printed'
set title 'x1: median over 200 runs, 5-95 % band (clipped at +-10)'
plot '/tmp/paper001.csv' skip 1 using 1:32:34 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/paper001.csv' skip 1 using 1:33 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/paper001.csv' skip 1 using 1:41:43 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/paper001.csv' skip 1 using 1:42 with lines lw 1.5 lc rgb '#D55E00' title 'ekf', \
     '/tmp/paper001.csv' skip 1 using 1:50:52 with filledcurves fs transparent solid 0.2 noborder lc rgb '#009E73' notitle, \
     '/tmp/paper001.csv' skip 1 using 1:51 with lines lw 1.5 lc rgb '#009E73' title 'ekf-printed'
set ylabel 'x2 - m'
set title 'x2: run 0 (clipped at +-10)'
plot '/tmp/paper001.csv' skip 1 using 1:9 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/paper001.csv' skip 1 using 1:15 with lines lw 1.5 lc rgb '#D55E00' title 'ekf', \
     '/tmp/paper001.csv' skip 1 using 1:21 with lines lw 1.5 lc rgb '#009E73' title 'ekf-printed'
set title 'x2: median over 200 runs, 5-95 % band (clipped at +-10)'
plot '/tmp/paper001.csv' skip 1 using 1:36:38 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/paper001.csv' skip 1 using 1:37 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/paper001.csv' skip 1 using 1:45:47 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/paper001.csv' skip 1 using 1:46 with lines lw 1.5 lc rgb '#D55E00' title 'ekf', \
     '/tmp/paper001.csv' skip 1 using 1:54:56 with filledcurves fs transparent solid 0.2 noborder lc rgb '#009E73' notitle, \
     '/tmp/paper001.csv' skip 1 using 1:55 with lines lw 1.5 lc rgb '#009E73' title 'ekf-printed'
unset multiplot
set output
