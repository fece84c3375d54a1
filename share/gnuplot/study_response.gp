# The response of a parametric study against its (first) parameter: peak
# stress, strain at peak, Young's modulus and solid fraction, each the mean
# over the packing seeds, their standard deviation as error bars.
# Drawn by `post study --table`, which defines:
#   $study   rows: x  peak(MPa) sd  strain at peak(%) sd  E(GPa) sd
#            solid fraction(%) sd   (sd 0 for a single run); one dataset
#            (index) per value of the second parameter
#   ngroups, group_title[k] (the legend; '' for a one-parameter study),
#   has_sd, title_text, xlabel_text, categorical (the values are words,
#   at x = 0, 1, ...), nx, xtics_cmd (their names as tic labels),
#   flat[c] (the one value of panel c when all are equal, else NaN)
set multiplot layout 2, 2 title title_text noenhanced
set xlabel xlabel_text noenhanced
if (categorical) eval xtics_cmd; set xrange [-0.5:nx - 0.5]; set offsets 0, 0, graph 0.06, 0
if (ngroups > 1) set key top left noenhanced font ',9'; else unset key
yrange(c) = flat[c] == flat[c] ? sprintf("set yrange [%g:%g]", \
            flat[c] - 0.05 * abs(flat[c]) - 1e-9, flat[c] + 0.05 * abs(flat[c]) + 1e-9) \
            : "set yrange [*:*]"
panel(c) = sprintf("plot for [k=1:ngroups] $study index k-1 using 1:%d%s with %s lt k " . \
                   "title group_title[k]", c, has_sd ? sprintf(":%d", c + 1) : "", \
                   has_sd ? "yerrorlines" : "linespoints")
set ylabel 'peak stress (MPa)'
eval yrange(1)
eval panel(2)
set ylabel 'strain at peak (%)'
eval yrange(2)
eval panel(4)
set ylabel "Young's modulus (GPa)"
eval yrange(3)
eval panel(6)
set ylabel 'solid fraction (%)'
eval yrange(4)
eval panel(8)
unset multiplot
