# Axial stress against axial strain (solid) and radial strain (dashed), as
# rock mechanics plots them, with experimental points when given; for a
# Brazilian test, the splitting tensile stress against the axial strain.
# Drawn by `post curve`, which defines:
#   $curve   rows: axial strain(%) stress(MPa) radial strain(%)
#            volumetric strain(%)   (NaN where the run has no value)
#   $exp     rows as $curve: experimental points;  has_exp, exp_label
#   has_radial;  pc  largest confining pressure (MPa, 0 for none)
#   bts      1: the stress is a Brazilian test's 2P/(π D t) (no radial strain)
set title (bts ? 'Brazilian test: splitting tensile stress' : \
           pc > 0 ? sprintf('Stress-strain curve (confining pressure %.3g MPa)', pc) \
                  : 'Stress-strain curve')
set xlabel (bts ? "axial strain ε_a (%): the platens' approach over the diameter" : \
            has_radial ? 'strain (%)      radial ε_r ←  0  → axial ε_a' : 'axial strain ε_a (%)')
set ylabel (bts ? 'splitting tensile stress σ_t = 2P/(π D t) (MPa)' : 'axial stress σ_a (MPa)')
set yrange [0:*]
set key bottom right
cmd = "plot $curve using 1:2 with lines lt 1 title (bts ? 'σ_t = 2P/(π D t)' : 'axial strain ε_a')"
if (has_radial) cmd = cmd . ", $curve using 3:2 with lines lt 2 dt (12,6) title 'radial strain ε_r'"
if (has_exp) cmd = cmd . ", $exp using 1:2 with points pt 6 ps 1.2 lc rgb '#000000' title exp_label . (bts ? '' : ' (axial)')"
if (has_exp && !bts) cmd = cmd . ", $exp using 3:2 with points pt 4 ps 1.2 lc rgb '#555555' title exp_label . ' (radial)'"
eval cmd
