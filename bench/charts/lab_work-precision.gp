# Work against precision, from `lab work-precision`'s CSV:
#   integrator,iterations,h_s,error_m,error_px,largest_px,cost_s_per_s
# x: CPU seconds per simulated second (log); y: RMS error on the image (px, log). One line per
# integrator (and iteration count for xpbd and projective), steps halving along it.
load "bench/charts/lab_common.gp"
set logscale xy 10
set format x "1e%L"
set format y "1e%L"
set xlabel "cost: CPU seconds per simulated second (one thread, float)"
set ylabel "RMS error of the nodes on a 1280x720 image (px)"
set title "Work against precision: breeze, 32x24 nodes, 0.2 s from rest, against converged RK4"
set arrow from graph 0, first 1 to graph 1, first 1 nohead dashtype 2 linecolor rgb "#555555"
iterated(name, iterations, column) = strcol(1) eq name && strcol(2) eq iterations ? column(column) : NaN
plot for [i=1:5] csv skip 1 using (only(word(integrators, i), 7)):(only(word(integrators, i), 5)) \
       with linespoints linewidth 1.5 pointtype 7 linecolor rgb colour(i) title word(integrators, i), \
     for [n in "2 10 50"] csv skip 1 using (iterated("xpbd", n, 7)):(iterated("xpbd", n, 5)) \
       with linespoints linewidth 1.2 pointtype (n eq "2" ? 4 : n eq "10" ? 6 : 8) linecolor rgb colour(6) title "xpbd, ".n." iterations", \
     csv skip 1 using (only("implicit_euler", 7)):(only("implicit_euler", 5)) \
       with linespoints linewidth 1.5 pointtype 7 linecolor rgb colour(7) title "implicit_euler", \
     for [n in "2 10 50"] csv skip 1 using (iterated("projective", n, 7)):(iterated("projective", n, 5)) \
       with linespoints linewidth 1.2 pointtype (n eq "2" ? 4 : n eq "10" ? 6 : 8) linecolor rgb colour(8) title "projective, ".n." iterations"
