# Cracks in an axial section: each crack within `thickness`/2 of the plane
# through the axis at angle psi, drawn as its trace (a segment of length
# 2 r_c across its normal). Drawn by `post cracks`, which defines:
#   $tension, $shear   rows: u h du dh (mm), segment start and extent
#   H, R   specimen height and radius (mm);  thickness (mm);  psi (deg)
#   ntension, nshear   crack counts in the whole specimen
set title sprintf("Cracks in the axial section at %g° (slab %.2g mm)", psi, thickness)
set xlabel 'distance across the axis (mm)'
set ylabel 'height (mm)'
set size ratio -1
set xrange [-1.1 * R:1.1 * R]
set yrange [-0.05 * H:1.05 * H]
set object 1 rectangle from -R,0 to R,H fillstyle empty border lc rgb '#888888' lw 1.5
set key at screen 0.5, 0.03 center bottom horizontal
set bmargin 7
plot $tension using 1:2:3:4 with vectors nohead lw 2 lc rgb tension_colour title 'tension', \
     $shear using 1:2:3:4 with vectors nohead lw 2 lc rgb shear_colour title 'shear'
