# Intact and damaged contacts apart, and the shear stress, against the
# contact orientation theta. Drawn by `post ratios`, which defines:
#   $all, $intact, $damaged   datablocks, one index per run, rows:
#            theta_mid(deg) r r_std tau/ref tau_std/ref count
#   nruns    number of runs;  label[k]  legend text of run k
#   ndamaged number of damaged contacts in compression (all runs)
#   min_count  fewest contacts a drawn bin has (fewer: NaN, not drawn)
set multiplot layout 1,2
set label 1002 sprintf('bins of fewer than %d contacts not drawn', min_count) \
    at screen 0.005, 0.008 left font ',7' tc rgb '#777777'
set xlabel 'angle θ between contact normal and horizontal plane (°)'
set xrange [0:90]
set xtics 0,10,90
set yrange [0:*]
set key top left
set title ndamaged > 0 ? 'Normal stress: intact (solid) and damaged (dashed) contacts' \
                       : 'Normal stress at intact contacts (none is damaged)'
set ylabel 'mean σ_n / σ@_a^{ref}'
cmd = "plot for [k=1:nruns] $intact index k-1 using 1:2 with linespoints lt k title label[k]"
if (ndamaged > 0) cmd = cmd . \
    ", for [k=1:nruns] $damaged index k-1 using 1:2 with linespoints lt k dt 2 pt 6 notitle" . \
    ", NaN with lines lc rgb '#444444' title 'intact'" . \
    ", NaN with lines lc rgb '#444444' dt 2 title 'damaged'"
eval cmd
set title 'Shear stress at bonded contacts in compression'
set ylabel 'mean τ / σ@_a^{ref}  (τ = |F_s| / A)'
set key bottom center
plot for [k=1:nruns] $all index k-1 using 1:4 with linespoints lt k title label[k]
unset multiplot
