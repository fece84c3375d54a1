# Cracks on the unrolled lateral surface: angle around the axis against
# height, with the true aspect of the unrolled cylinder (width pi D).
# Drawn by `post cracks`, which defines:
#   $tension, $shear   rows: phi(deg) height(mm) of cracks within `depth`
#                      of the lateral surface
#   H, R   specimen height and radius (mm);  depth (mm)
#   ntension, nshear   crack counts in the whole specimen
set title sprintf('Cracks on the unrolled lateral surface (within %.2g mm of it)', depth)
set xlabel 'angle around the axis φ (°)'
set ylabel 'height (mm)'
set xrange [0:360]
set xtics 0,45,360
set yrange [0:H]
set size ratio H / (2 * pi * R)
set key at screen 0.5, 0.03 center bottom horizontal
set bmargin 7
plot $tension using 1:2 with points pt 7 ps 0.7 lc rgb tension_colour \
        title sprintf('tension (%d in the specimen)', ntension), \
     $shear using 1:2 with points pt 9 ps 0.8 lc rgb shear_colour \
        title sprintf('shear (%d in the specimen)', nshear)
