# Shared by the lab charts: terminal, CSV input, one colour per integrator.
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1100,720 font "sans,11"
} else {
  set terminal png size 1100,720
}
set output png
set datafile separator ","
set grid xtics ytics mxtics mytics
set key inside bottom left box opaque font ",9"
set termoption noenhanced  # integrator names have underscores
integrators = "symplectic_euler seed explicit_euler verlet rk4 xpbd implicit_euler projective"
colours = "#1f77b4 #17becf #d62728 #ff7f0e #2ca02c #9467bd #8c564b #e377c2"
colour(i) = word(colours, i)
# The value of `column` in rows whose first field is integrator `name`, else undefined.
only(name, column) = strcol(1) eq name ? column(column) : NaN
# Plot styles join the points of one series after sorting by x, skipping other series' rows
# (undefined there): `smooth unique`.
