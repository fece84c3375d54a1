# Achieved against target: the error of each target at the start, at the
# calibrated point on the search specimens and on the confirming (full)
# specimens, with the tolerance as a band.
# Drawn by `calibrate`, which defines:
#   $targets  rows: index "test\nquantity" start(%) calibrated(%) confirm(%)
#             tolerance(%)  (NaN where not run)
#   ntargets, has_confirm, title_text
set title 'Calibration: ' . title_text noenhanced
set ylabel 'error against the target (%)'
set xrange [-0.6:ntargets - 0.4]
set xtics noenhanced
set offsets 0, 0, graph 0.08, graph 0.08
set key at screen 0.5, 0.03 center bottom horizontal
set bmargin 7
set style fill transparent solid 0.15 noborder
cmd = "plot $targets using 1:(0):($1 - 0.4):($1 + 0.4):(-$6):6:xtic(2) with boxxyerror" . \
      " lc rgb '#009E73' title 'tolerance'," . \
      " $targets using ($1 - 0.15):3 with points lt 7 pt 4 ps 1.4 title 'start'," . \
      " $targets using 1:4 with points lt 1 pt 7 ps 1.6 title 'calibrated (search specimen)'"
if (has_confirm) cmd = cmd . ", $targets using ($1 + 0.15):5 with points lt 2 pt 5 ps 1.4" . \
      " title 'confirming specimen'"
eval cmd
