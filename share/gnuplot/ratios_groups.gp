# Intact and damaged contacts apart, and the shear stress, against the
# contact orientation theta. Drawn by `post ratios`, which defines:
#   $all, $intact, $damaged   datablocks, one index per run, rows:
#            theta_mid(deg) r r_std tau/ref tau_std/ref count
#   nruns    number of runs;  label[k]  legend text of run k
#   ndamaged number of damaged contacts in compression (all runs)
#   min_count  fewest contacts a drawn bin has (fewer: NaN, not drawn)
#   canvas_h   figure height (pixels);  key_rows  rows of the legend
# From the foot up: the footer (the run files), the note on the bins not
# drawn, one legend for both panels (the runs, and solid intact and
# dashed damaged contacts) and the two panels side by side, so that
# nothing covers anything.
row_px = 21.0
note_y = 22.0 / canvas_h
key_top = (40.0 + row_px * key_rows) / canvas_h
set multiplot layout 1,2
set label 1002 sprintf('bins of fewer than %d contacts not drawn', min_count) \
    at screen 0.005, note_y left font ',7' tc rgb '#777777'
set bmargin at screen key_top + 68.0 / canvas_h
set tmargin at screen 1 - 45.0 / canvas_h
set xlabel 'angle θ between contact normal and horizontal plane (°)'
set xrange [0:90]
set xtics 0,10,90
set yrange [0:*]
set key at screen 0.5, key_top center top vertical Left reverse spacing 1.25 width -1
set title ndamaged > 0 ? 'Normal stress: intact (solid) and damaged (dashed) contacts' \
                       : 'Normal stress at intact contacts (none is damaged)'
set ylabel 'mean σ_n / σ@_a^{ref}'
cmd = "plot for [k=1:nruns] $intact index k-1 using 1:2 with linespoints lt k title label[k]"
if (ndamaged > 0) cmd = cmd . \
    ", for [k=1:nruns] $damaged index k-1 using 1:2 with linespoints lt k dt 2 pt 6 notitle" . \
    ", NaN with lines lc rgb '#444444' title 'intact contacts'" . \
    ", NaN with lines lc rgb '#444444' dt 2 title 'damaged contacts'"
eval cmd
# The legend, the note and the footer are drawn once, with the left panel.
unset key
unset label 1001
unset label 1002
set title 'Shear stress at bonded contacts in compression'
set ylabel 'mean τ / σ@_a^{ref}  (τ = |F_s| / A)'
plot for [k=1:nruns] $all index k-1 using 1:4 with linespoints lt k notitle
unset multiplot
