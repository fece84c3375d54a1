# Volumetric strain against axial strain (compression positive): the turn
# from compaction to dilatancy. Drawn by `post curve`, which defines:
#   $curve, $exp, has_exp, exp_label, pc   as for stress_strain.gp
set title 'Volumetric strain'
set xlabel 'axial strain ε_a (%)'
set ylabel 'volumetric strain ε_v (%)   (compression positive)'
set key top left
cmd = "plot $curve using 1:4 with lines lt 1 title 'ε_v'"
if (has_exp) cmd = cmd . ", $exp using 1:4 with points pt 6 ps 1.2 lc rgb '#000000' title exp_label"
eval cmd
