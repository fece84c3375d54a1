# Cumulative cracks (broken bonds) by mode against axial strain, with the
# axial stress on the right axis when `with_stress` is 1.
# Drawn by `post cracks` and `post curve`, which define:
#   $count    rows: axial strain(%) tension shear total (cumulative)
#   cracks    the number of cracks (broken bonds)
#   $stress   rows: axial strain(%) axial stress(MPa)   (with_stress = 1);
#             bts = 1: a Brazilian test's splitting tensile stress instead
set title 'Broken bonds by failure mode'
set xlabel 'axial strain ε_a (%)'
set ylabel 'broken bonds (cumulative)'
# No crack yet: a range of 0 to 1 (gnuplot would warn of an empty one).
if (cracks > 0) {
	set yrange [0:*]
} else {
	set yrange [0:1]
}
set key top left
if (with_stress) {
	set y2label (bts ? 'splitting tensile stress σ_t = 2P/(π D t) (MPa)' : 'axial stress σ_a (MPa)')
	set y2tics
	set y2range [0:*]
	plot $count using 1:2 with steps lw 2 lc rgb tension_colour title 'tension', \
	     $count using 1:3 with steps lw 2 lc rgb shear_colour title 'shear', \
	     $count using 1:4 with steps lw 2 lc rgb '#444444' dt 2 title 'all', \
	     $stress using 1:2 axes x1y2 with lines lw 1.5 lc rgb '#009E73' title (bts ? 'tensile stress σ_t' : 'axial stress')
} else {
	plot $count using 1:2 with steps lw 2 lc rgb tension_colour title 'tension', \
	     $count using 1:3 with steps lw 2 lc rgb shear_colour title 'shear', \
	     $count using 1:4 with steps lw 2 lc rgb '#444444' dt 2 title 'all'
}
