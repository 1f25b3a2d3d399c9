# Thread sweep, from `lab threads`'s CSV:
#   integrator,cols,rows,threads,ms_per_step,speedup,efficiency
load "bench/charts/lab_common.gp"
set logscale x 2
set xlabel "nodes"
set ylabel "speedup over one thread (wall time)"
set title "Threads: speedup per step, breeze preset"
at(name, threads, column) = strcol(1) eq name && column(4) == threads ? column(column) : NaN
plot for [t=2:4] csv skip 1 using (at("symplectic_euler", t, 2) * column(3)):(at("symplectic_euler", t, 6)) \
       smooth unique with linespoints linewidth 1.5 pointtype 7 linecolor rgb colour(t) title "symplectic_euler, ".t." threads", \
     for [t=2:4] csv skip 1 using (at("implicit_euler", t, 2) * column(3)):(at("implicit_euler", t, 6)) \
       smooth unique with linespoints linewidth 1.5 pointtype 4 dashtype 2 linecolor rgb colour(t) title "implicit_euler, ".t." threads", \
     1.8 with lines dashtype 3 linecolor rgb "#555555" title "target at 2 threads: 1.8x"
