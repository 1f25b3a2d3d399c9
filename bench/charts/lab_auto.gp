# screen_error against cost, from `lab auto`'s second CSV (auto-models.csv):
#   scene,distance,image,model,method,cols,cost,time_px,resolution_px,measured_px,auto
# One panel per preset at 1280x720: every fixed model auto could run (a method on a grid of its
# ladder), flown 1 s from the same state, its measured screen_error (frame defect plus the grid's
# resolution error) against its cost by the cost model; filled at the preset's own camera, open
# ten times farther; auto's choice at each ringed in black. The dashed line is the 1 px budget.
#   gnuplot -e "csv='docs/lab/auto-models.csv'; png='docs/lab/auto.png'" bench/charts/lab_auto.gp
load "bench/charts/lab_common.gp"
set terminal pngcairo size 1200,900 font "sans,10"
set termoption noenhanced
set output png
set logscale xy 10
set format x "1e%L"
set format y "1e%L"
set xlabel "cost: CPU seconds per simulated second (cost model, one thread)"
set ylabel "screen_error measured (px)"
set key inside bottom left box opaque font ",8"
methods = "symplectic_euler verlet rk4 xpbd"
method_colour(i) = colour(i == 1 ? 1 : i == 2 ? 4 : i == 3 ? 5 : 6)
at(scene, distance, method, column) = strcol(1) eq scene && column(2) == distance && strcol(3) eq "1280x720" && \
                                      strcol(5) eq method ? column(column) : NaN
chosen(scene, distance, column) = strcol(1) eq scene && column(2) == distance && strcol(3) eq "1280x720" && \
                                  column(11) == 1 ? column(column) : NaN
set multiplot layout 2,2 title "What auto chooses among every fixed model (1 s after a switch, 1280x720)"
do for [scene in "breeze calm gale hanging"] {
  set title scene
  if (scene ne "breeze") { unset key }
  set arrow 1 from graph 0, first 1 to graph 1, first 1 nohead dashtype 2 linecolor rgb "#555555"
  plot for [i=1:4] csv skip 1 using (at(scene, 1, word(methods, i), 7)):(at(scene, 1, word(methods, i), 10)) \
         with points pointtype 7 pointsize 1.1 linecolor rgb method_colour(i) title word(methods, i)." (own camera)", \
       for [i=1:4] csv skip 1 using (at(scene, 10, word(methods, i), 7)):(at(scene, 10, word(methods, i), 10)) \
         with points pointtype 6 pointsize 1.1 linecolor rgb method_colour(i) title word(methods, i)." (10x farther)", \
       csv skip 1 using (chosen(scene, 1, 7)):(chosen(scene, 1, 10)) \
         with points pointtype 6 pointsize 3 linewidth 2 linecolor rgb "black" title "auto's choice", \
       csv skip 1 using (chosen(scene, 10, 7)):(chosen(scene, 10, 10)) \
         with points pointtype 6 pointsize 3 linewidth 2 linecolor rgb "black" notitle
}
unset multiplot
