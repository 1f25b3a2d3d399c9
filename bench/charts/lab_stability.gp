# The stability map, from `lab stability`'s CSV:
#   integrator,stiffness_N_per_m,w_max_rad_per_s,largest_stable_h_s,theory_h_s,states_theory_h_s,
#   measured_over_states,claimed_h_s
# x: structural stiffness (log); y: step (log). Points: the largest stable step found by
# bisection; lines: the theory on the stiffest mode of the states the flag passes through (2/w
# for symplectic Euler and Verlet, 2 sqrt(2)/w for RK4, the mode's damping bound for explicit Euler).
load "bench/charts/lab_common.gp"
set logscale xy 10
set format x "1e%L"
set format y "1e%L"
set xlabel "structural stiffness (N/m); shear and bending stiffness scaled with it"
set ylabel "largest stable step (s)"
set title "Stability map: 16x12 nodes, 1 s from rest in a steady breeze (unconditionally stable methods pass 0.1 s)"
plot for [i in "1 3 4 5"] csv skip 1 using (only(word(integrators, int(i)), 2)):(only(word(integrators, int(i)), 4)) \
       with points pointtype 7 pointsize 1.4 linecolor rgb colour(int(i)) title word(integrators, int(i)).", measured", \
     csv skip 1 using (only("symplectic_euler", 2)):(only("symplectic_euler", 6)) \
       smooth unique with lines linewidth 2 dashtype 2 linecolor rgb colour(1) title "2 / w (symplectic Euler, Verlet)", \
     csv skip 1 using (only("rk4", 2)):(only("rk4", 6)) \
       smooth unique with lines linewidth 2 dashtype 2 linecolor rgb colour(5) title "2 sqrt(2) / w (RK4)", \
     csv skip 1 using (only("explicit_euler", 2)):(only("explicit_euler", 6)) \
       smooth unique with lines linewidth 2 dashtype 2 linecolor rgb colour(3) title "damping bound (explicit Euler)", \
     csv skip 1 using (only("symplectic_euler", 2)):(only("symplectic_euler", 8)) \
       smooth unique with lines linewidth 1 dashtype 3 linecolor rgb colour(1) title "claimed by the bound (symplectic Euler)"
