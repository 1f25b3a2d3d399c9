# Cost per node-substep, from `lab cost`'s CSV:
#   integrator,cols,rows,nodes,substeps,ms_per_step,ns_per_node_substep,bytes_per_node
load "bench/charts/lab_common.gp"
set logscale x 10
set logscale y 10
set format x "1e%L"
set xlabel "nodes"
set ylabel "ns per node-substep (one thread, float)"
set title "Cost per node-substep, breeze preset, 32x24 to 512x384 nodes"
plot for [i=1:8] csv skip 1 using (only(word(integrators, i), 4)):(only(word(integrators, i), 7)) \
       smooth unique with linespoints linewidth 1.5 pointtype 7 linecolor rgb colour(i) title word(integrators, i)
