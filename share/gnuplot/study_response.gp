# The response of a parametric study against its (first) parameter: four
# panels (peak stress, strain at peak, Young's modulus and solid fraction;
# a Brazilian test's strength and broken bonds in place of the first and
# third), each the mean over the packing seeds, their standard deviation
# as error bars.
# Drawn by `post study --table`, which defines:
#   $study   rows: x, then the four panels' mean and sd (sd 0 for a
#            single run); one dataset
#            (index) per value of the second parameter
#   ngroups, group_title[k] (the legend; '' for a one-parameter study),
#   has_sd, title_text, xlabel_text, categorical (the values are words,
#   at x = 0, 1, ...), nx, xtics_cmd (their names as tic labels),
#   flat[c] (the one value of panel c when all are equal, else NaN),
#   empty[c] (1: panel c has no value), ylabel_text[c], xmin, xmax
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
do for [c=1:4] {
    set ylabel ylabel_text[c] noenhanced
    if (empty[c]) {
        # Not measured by this test (e.g. Young's modulus of a Brazilian test).
        if (!categorical) { set xrange [xmin:xmax] }
        set yrange [0:1]
        set label 1 'not measured by this test' at graph 0.5, 0.5 center
        plot 1/0 notitle
        unset label 1
        if (!categorical) { set xrange [*:*] }
    } else {
        eval yrange(c)
        eval panel(2 * c)
    }
}
unset multiplot
