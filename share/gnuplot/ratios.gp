# Micro-macro compressive stress ratio r = mean sigma_n / sigma_ref against
# the contact orientation theta, one line per run (Onate et al. 2015,
# Fig. 11). Drawn by `post ratios`, which defines before this script:
#   $all     datablock, one index per run, rows:
#            theta_mid(deg) r r_std tau/ref tau_std/ref count
#            (NaN in an empty bin, or one with fewer than min_count
#            contacts: the line stops there)
#   nruns    number of runs;  label[k]  legend text of run k
#   min_count  fewest contacts a drawn bin has
#   canvas_h   figure height (pixels);  key_rows  rows of the legend
# From the foot up: the footer (the run files), the note on the bins not
# drawn, the legend and the plot, so that nothing covers anything.
row_px = 21.0
note_y = 22.0 / canvas_h
key_top = (40.0 + row_px * key_rows) / canvas_h
set bmargin at screen key_top + 68.0 / canvas_h
set label 1002 sprintf('bins of fewer than %d contacts not drawn', min_count) \
    at screen 0.005, note_y left font ',7' tc rgb '#777777'
set key at screen 0.5, key_top center top vertical Left reverse spacing 1.25 width -1
set title 'Micro-macro compressive stress ratio by contact orientation'
set xlabel 'angle θ between contact normal and horizontal plane (°)'
set ylabel 'r = mean σ_n / σ@_a^{ref}'
set xrange [0:90]
set xtics 0,10,90
set yrange [0:*]
# The range Onate et al. 2015 found for cement, for comparison.
set object 1 rectangle from 0,0.55 to 90,0.65 behind fillcolor rgb '#ececec' fillstyle solid noborder
# Runs are shifted by a fraction of a degree so error bars do not overlap.
shift(k) = 0.6 * (k - 0.5 * (nruns + 1))
plot for [k=1:nruns] $all index k-1 using ($1 + shift(k)):2:3 with yerrorbars lt k lw 1 pt -1 notitle, \
     for [k=1:nruns] $all index k-1 using ($1 + shift(k)):2 with linespoints lt k title label[k], \
     NaN with filledcurves fillcolor rgb '#ececec' title 'r = 0.55-0.65, cement (Oñate et al. 2015)' 
