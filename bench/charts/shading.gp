# Speed against accuracy of the shading modes, from shading_bench's CSV:
#   gnuplot -e "csv='docs/shading.csv'; png='docs/shading.png'" bench/charts/shading.gp
# CSV: a header line, then mode,cols,rows,ms,psnr_image_db,psnr_flag_db, each mode's rows together.
# x: median time per frame (ms, log scale); y: PSNR of the flag's pixels against the reference
# (dB). One point per mode and flag grid, labelled with the grid; a mode's grids joined by a line.
# Left: every mode; right: the filled modes (flat, Gouraud, Phong) on a narrower PSNR scale.

if (!exists("csv")) csv = "docs/shading.csv"
if (!exists("png")) png = "docs/shading.png"

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
  set terminal pngcairo size 1400,640 font "sans,11"
} else {
  set terminal png size 1400,640
}
set output png
set datafile separator ","
set key top left box opaque
set grid xtics ytics mxtics
set logscale x 10
set format x "%g"
set xlabel "time per frame, median of 30 (ms, log scale)"
set ylabel "PSNR of the flag's pixels against the reference (dB)"

modes = "wireframe flat gouraud phong"
titles = "wireframe flat Gouraud Phong"
colours = "#7f7f7f #d62728 #1f77b4 #2ca02c"
grids = "16 32 64"  # cols of the three flag grids
# Label offsets (characters) per grid, so that labels of close points stay apart:
# 16x12 below left, 32x24 above, 64x48 to the right.
offset_x(j) = j == 1 ? -5.5 : j == 2 ? -2.0 : 0.8
offset_y(j) = j == 1 ? -0.9 : j == 2 ? 1.0 : 0.0

# The value of `column` in the rows of mode `mode` (and of grid `cols`, if not 0), else undefined.
only(mode, column) = strcol(1) eq mode ? column(column) : NaN
only_grid(mode, cols, column) = strcol(1) eq mode && column(2) == cols ? column(column) : NaN
grid_name(dummy) = strcol(2) . "x" . strcol(3)

# Axis ranges from the data: all rows for the left panel, the filled modes' for the right one.
stats csv skip 1 using 4:6 name "all" nooutput
stats csv skip 1 using (strcol(1) ne "wireframe" ? column(4) : NaN):6 name "filled_ms" nooutput
stats csv skip 1 using (strcol(1) ne "wireframe" ? column(6) : NaN) name "filled_db" nooutput
zoom_x_low = filled_ms_min_x / 1.5
zoom_x_high = filled_ms_max_x * 2.2
zoom_y_low = floor(filled_db_min - 0.5)
zoom_y_high = ceil(filled_db_max + 0.5)

set multiplot layout 1,2 title "Shading modes: time against accuracy, 1280x720, 2 threads; reference = 4x4 supersampled Phong" font ",13"

set title "all modes (dashed box: the right-hand panel)"
set xrange [all_min_x / 2:all_max_x * 3]
set yrange [0:zoom_y_high + 5]
set object 1 rectangle from zoom_x_low,zoom_y_low to zoom_x_high,zoom_y_high fillstyle empty border linecolor rgb "#555555" dashtype 2
plot for [i=1:4] csv skip 1 using (only(word(modes, i), 4)):6 with linespoints \
       linewidth 1.5 pointtype 7 pointsize 1.3 linecolor rgb word(colours, i) title word(titles, i), \
     for [j=1:3] csv skip 1 using (only_grid("wireframe", int(word(grids, j)), 4)):6:(grid_name(0)) \
       with labels offset char offset_x(j),offset_y(j) left font ",9" textcolor rgb word(colours, 1) notitle
unset object 1

set title "filled modes, PSNR scale zoomed"
set xrange [zoom_x_low:zoom_x_high]
set yrange [zoom_y_low:zoom_y_high]
plot for [i=2:4] csv skip 1 using (only(word(modes, i), 4)):6 with linespoints \
       linewidth 1.5 pointtype 7 pointsize 1.3 linecolor rgb word(colours, i) title word(titles, i), \
     for [i=2:4] for [j=1:3] csv skip 1 using (only_grid(word(modes, i), int(word(grids, j)), 4)):6:(grid_name(0)) \
       with labels offset char offset_x(j),offset_y(j) left font ",9" textcolor rgb word(colours, i) notitle

unset multiplot
