# Cracks in an axial section: each crack within `thickness`/2 of the plane
# through the axis at angle psi, drawn as its trace (a segment of length
# 2 r_c across its normal). For a Brazilian test (disc = 1), the disc's
# face instead: the plane through its centre normal to its axis, with the
# loading diameter vertical, cracks within `thickness`/2 of it.
# Drawn by `post cracks`, which defines:
#   $tension, $shear   rows: u h du dh (mm), segment start and extent
#                      (disc: h along the loading diameter from the centre)
#   H, R   specimen height (disc: thickness) and radius (mm);
#   thickness (mm);  psi (deg);  disc
#   ntension, nshear   crack counts in the whole specimen
set size ratio -1
set xrange [-1.1 * R:1.1 * R]
if (disc) {
	set title (thickness >= H ? sprintf("Cracks seen on the face of the disc (its whole %.2g mm thickness)", H) \
	                          : sprintf("Cracks seen on the face of the disc (a %.2g mm slab of its %.2g mm thickness)", thickness, H))
	set xlabel 'across the loading diameter (mm)'
	set ylabel 'along the loading diameter (mm)'
	set yrange [-1.1 * R:1.1 * R]
	set object 1 circle at 0,0 size R fillstyle empty border lc rgb '#888888' lw 1.5
	# Where the platens press, at the ends of the loading diameter.
	set arrow 1 from -0.5 * R,R to 0.5 * R,R nohead lc rgb '#888888' lw 3
	set arrow 2 from -0.5 * R,-R to 0.5 * R,-R nohead lc rgb '#888888' lw 3
} else {
	set title sprintf("Cracks in the axial section at %g° (slab %.2g mm)", psi, thickness)
	set xlabel 'distance across the axis (mm)'
	set ylabel 'height (mm)'
	set yrange [-0.05 * H:1.05 * H]
	set object 1 rectangle from -R,0 to R,H fillstyle empty border lc rgb '#888888' lw 1.5
}
set key at screen 0.5, 0.03 center bottom horizontal
set bmargin 7
plot $tension using 1:2:3:4 with vectors nohead lw 2 lc rgb tension_colour title 'tension', \
     $shear using 1:2:3:4 with vectors nohead lw 2 lc rgb shear_colour title 'shear'
