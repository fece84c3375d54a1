# How a calibration converged: at each evaluated point, the largest error
# over the targets as a multiple of its tolerance (below 1 every target is
# met), the same predicted for the point's best scaled copy (with the exact
# scaling), and the best point so far.
# Drawn by `calibrate`, which defines:
#   $path   rows: point  worst  scaled_worst  best_worst  round
#           (NaN where a point failed, or has no scaled copy)
#   title_text
set title 'Calibration: ' . title_text noenhanced
set xlabel 'point evaluated'
set ylabel 'largest error / tolerance'
set logscale y
set format y '10^{%L}'
set yrange [*:*]
set offsets 0.5, 0.5, 0, 0
# Whole points on the x axis: a tick at each when there are few.
set format x '%.0f'
stats $path using 1 nooutput
if (STATS_max < 12) set xtics 1
set key below maxrows 2 width 2
set bmargin 7
# The last curve, not drawn, keeps the axis below the tolerance line
# however far above it the points stay.
plot $path using 1:2 with points lt 1 pt 7 title 'point (its runs)', \
     $path using 1:3 with points lt 2 pt 6 title 'its best scaled copy (predicted)', \
     $path using 1:4 with steps lt 3 lw 2 title 'best so far', \
     1 with lines lt 7 dt 2 lw 1 title 'tolerance', \
     0.3 with lines lt nodraw notitle
