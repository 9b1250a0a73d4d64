# pfgen simulate: estimation errors x - m of every filter against time.
# Data: /tmp/ins16.csv (pfgen results CSV; columns by position, header skipped).
set terminal pngcairo size 1000,10280 noenhanced font 'Sans,10'
set output 'docs/figures/ins16_errors.png'
set datafile separator comma
set multiplot layout 32,1 title 'ins16: estimation errors x - m'
set grid
set key outside right top
set xlabel 't'
set lmargin 12
set rmargin 24
set xrange [0:10]
set ylabel 'q0 - m'
set title 'q0: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:50 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:98 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'q0: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:180:182 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:181 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:245:247 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:246 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'q1 - m'
set title 'q1: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:51 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:99 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'q1: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:184:186 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:185 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:249:251 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:250 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'q2 - m'
set title 'q2: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:52 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:100 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'q2: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:188:190 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:189 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:253:255 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:254 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'q3 - m'
set title 'q3: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:53 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:101 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'q3: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:192:194 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:193 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:257:259 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:258 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'vn - m'
set title 'vn: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:54 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:102 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'vn: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:196:198 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:197 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:261:263 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:262 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 've - m'
set title 've: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:55 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:103 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 've: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:200:202 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:201 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:265:267 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:266 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'vd - m'
set title 'vd: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:56 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:104 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'vd: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:204:206 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:205 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:269:271 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:270 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'pn - m'
set title 'pn: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:57 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:105 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'pn: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:208:210 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:209 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:273:275 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:274 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'pe - m'
set title 'pe: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:58 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:106 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'pe: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:212:214 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:213 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:277:279 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:278 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'pd - m'
set title 'pd: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:59 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:107 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'pd: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:216:218 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:217 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:281:283 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:282 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'bgx - m'
set title 'bgx: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:60 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:108 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'bgx: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:220:222 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:221 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:285:287 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:286 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'bgy - m'
set title 'bgy: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:61 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:109 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'bgy: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:224:226 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:225 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:289:291 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:290 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'bgz - m'
set title 'bgz: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:62 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:110 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'bgz: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:228:230 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:229 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:293:295 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:294 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'bax - m'
set title 'bax: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:63 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:111 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'bax: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:232:234 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:233 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:297:299 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:298 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'bay - m'
set title 'bay: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:64 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:112 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'bay: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:236:238 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:237 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:301:303 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:302 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set ylabel 'baz - m'
set title 'baz: run 0'
plot '/tmp/ins16.csv' skip 1 using 1:65 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:113 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
set title 'baz: median over 20 runs, 5-95 % band'
plot '/tmp/ins16.csv' skip 1 using 1:240:242 with filledcurves fs transparent solid 0.2 noborder lc rgb '#0072B2' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:241 with lines lw 1.5 lc rgb '#0072B2' title 'optimal', \
     '/tmp/ins16.csv' skip 1 using 1:305:307 with filledcurves fs transparent solid 0.2 noborder lc rgb '#D55E00' notitle, \
     '/tmp/ins16.csv' skip 1 using 1:306 with lines lw 1.5 lc rgb '#D55E00' title 'ekf'
unset multiplot
set output
