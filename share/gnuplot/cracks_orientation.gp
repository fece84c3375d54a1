# Histogram of crack orientations by mode: the angle theta between the
# crack normal (the broken bond's direction) and the plane normal to the
# load; 0 deg is a vertical crack plane (axial splitting), 90 deg a
# horizontal one. Drawn by `post cracks`, which defines:
#   $hist   rows: bin centre(deg) bin width(deg) tension shear
set title 'Crack orientations'
set xlabel 'angle θ between crack normal and horizontal plane (°)   (0° vertical crack, 90° horizontal)'
set ylabel 'number of cracks'
set xrange [0:90]
set xtics 0,10,90
set yrange [0:*]
set style fill solid 0.9 border lc rgb '#333333'
set key top right
plot $hist using ($1 - $2 / 4):3:($2 / 2) with boxes lc rgb tension_colour title 'tension', \
     $hist using ($1 + $2 / 4):4:($2 / 2) with boxes lc rgb shear_colour title 'shear'
