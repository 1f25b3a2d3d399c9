# What self-collision buys against what it costs, from collision_bench's CSV:
#   gnuplot -e "csv='docs/collisions/cost.csv'; png='docs/collisions/crossings-vs-cost.png'" \
#     bench/charts/collisions.gp
# CSV: a header line, then preset,cols,rows,substeps,seconds,ms_off,ms_on,ratio,run_ms_off,
# run_ms_on,run_ratio,candidates,contacts,held,crossings_per_s_off,crossings_per_s_on.
# x: CPU ms per step over the run whose crossings were counted (run_ms_*, log scale); y: crossing
# pairs of triangles per simulated second (sum over the STATEs sampled at 60 Hz / seconds, log
# scale). One point per case and setting, labelled with the case; a case's two points joined.
# No crossing at all cannot sit on a log scale: it is drawn on the floor line, "none".

if (!exists("csv")) csv = "docs/collisions/cost.csv"
if (!exists("png")) png = "docs/collisions/crossings-vs-cost.png"

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1100,720 font "sans,11"
} else {
  set terminal png size 1100,720
}
set output png
set datafile separator ","
set termoption noenhanced
set grid xtics ytics mxtics mytics
set key top left box opaque
set logscale x 10
set logscale y 10
set format x "%g"
set format y "%g"
set xlabel "CPU ms per step over the run (one thread, log scale)"
set ylabel "crossing pairs of triangles per simulated second (log scale)"
set title "Self-collision: crossing pairs against cost per step, off and on, in one run"

floor = 0.1  # crossings per second drawn for "none"
at_floor(value) = value > 0 ? value : floor
case_name(dummy) = strcol(1) . " " . strcol(2) . "x" . strcol(3)
# Label offsets (characters) by preset, so that the three 32 x 24 cases' labels stay apart: off
# points' labels above right (calm's to the left, gale's below); on points' labels stacked under
# the floor line, where they all sit.
presets = "breeze calm gale"
off_dx = "1 -11 1"
off_dy = "0.8 0 -0.9"
on_dy = "-0.9 -1.9 -2.9"
# The value of `column` in rows of preset `name`, else undefined.
only(name, column) = strcol(1) eq name ? column(column) : NaN

stats csv skip 1 using 9 name "off_ms" nooutput
stats csv skip 1 using 10 name "on_ms" nooutput
stats csv skip 1 using (at_floor(column(16))) name "off_rate" nooutput
least_ms = off_ms_min < on_ms_min ? off_ms_min : on_ms_min
most_ms = off_ms_max > on_ms_max ? off_ms_max : on_ms_max
set xrange [least_ms / 2:most_ms * 3]
set yrange [floor / 8:(off_rate_max > 1 ? off_rate_max : 1) * 5]
set arrow 1 from graph 0, first floor to graph 1, first floor nohead dashtype 2 linecolor rgb "#555555"
set label 1 "none" at graph 0.01, first floor offset 0,0.6 textcolor rgb "#555555"

# Each case's two points joined: off (column 9, 16) then on (10, 17), a blank line between cases.
pairs = "< awk -F, 'NR > 1 { print $9 \",\" $16; print $10 \",\" $17; print \"\" }' " . csv

plot pairs using 1:(at_floor($2)) with lines linecolor rgb "#bbbbbb" notitle, \
     csv skip 1 using 9:(at_floor(column(16))) with points pointtype 7 pointsize 1.6 \
       linecolor rgb "#d62728" title "self_collision off", \
     csv skip 1 using 10:(at_floor(column(17))) with points pointtype 5 pointsize 1.6 \
       linecolor rgb "#1f77b4" title "self_collision on", \
     for [i=1:3] csv skip 1 using (only(word(presets, i), 9)):(at_floor(column(16))):(case_name(0)) \
       with labels offset char real(word(off_dx, i)),real(word(off_dy, i)) left font ",9" \
       textcolor rgb "#d62728" notitle, \
     for [i=1:3] csv skip 1 using (only(word(presets, i), 10)):(at_floor(column(17))):(case_name(0)) \
       with labels offset char 1,real(word(on_dy, i)) left font ",9" textcolor rgb "#1f77b4" notitle
