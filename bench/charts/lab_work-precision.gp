# Work against precision, from `lab work-precision`'s CSV:
#   integrator,iterations,h_s,error_m,error_px,largest_px,cost_s_per_s
# x: CPU seconds per simulated second (log); y: RMS error on the image (px, log). One line per
# integrator (and iteration count for xpbd and projective), steps halving along it. Given
# bullet='FILE' (bullet_bench --work-precision's CSV, the same columns), its "bullet" rows are
# drawn as separate points: Bullet's soft body at its own step and iterations.
load "bench/charts/lab_common.gp"
set logscale xy 10
set format x "1e%L"
set format y "1e%L"
set xlabel "cost: CPU seconds per simulated second (one thread, float)"
set ylabel "RMS error of the nodes on a 1280x720 image (px)"
set title "Work against precision: breeze, 32x24 nodes, 0.2 s from rest, against converged RK4"
set arrow from graph 0, first 1 to graph 1, first 1 nohead dashtype 2 linecolor rgb "#555555"
iterated(name, iterations, column) = strcol(1) eq name && strcol(2) eq iterations ? column(column) : NaN
# Bullet's points and, beside each, its step and iterations; a macro, empty without bullet=.
set style textbox opaque noborder
bullet_x = 'only("bullet", 7)'
bullet_y = 'only("bullet", 5)'
bullet_text = 'sprintf("Bullet, %g ms, %s iterations", 1e3 * column(3), strcol(2))'
bullet_points = !exists("bullet") ? "" : \
  ", bullet skip 1 using (".bullet_x."):(".bullet_y.") with points pointtype 5 pointsize 2.2 " . \
  "linecolor rgb 'black' title 'Bullet btSoftBody (its own step and iterations)', " . \
  "bullet skip 1 using (".bullet_x."):(".bullet_y."):(".bullet_text.") with labels left offset 1.5,0 boxed notitle"
plot for [i=1:5] csv skip 1 using (only(word(integrators, i), 7)):(only(word(integrators, i), 5)) \
       with linespoints linewidth 1.5 pointtype 7 linecolor rgb colour(i) title word(integrators, i), \
     for [n in "2 10 50"] csv skip 1 using (iterated("xpbd", n, 7)):(iterated("xpbd", n, 5)) \
       with linespoints linewidth 1.2 pointtype (n eq "2" ? 4 : n eq "10" ? 6 : 8) linecolor rgb colour(6) title "xpbd, ".n." iterations", \
     csv skip 1 using (only("implicit_euler", 7)):(only("implicit_euler", 5)) \
       with linespoints linewidth 1.5 pointtype 7 linecolor rgb colour(7) title "implicit_euler", \
     for [n in "2 10 50"] csv skip 1 using (iterated("projective", n, 7)):(iterated("projective", n, 5)) \
       with linespoints linewidth 1.2 pointtype (n eq "2" ? 4 : n eq "10" ? 6 : 8) linecolor rgb colour(8) title "projective, ".n." iterations" \
     @bullet_points
