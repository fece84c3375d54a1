# Common look of post's figures, loaded before every other script of this
# directory: eight distinguishable line types (colour-blind safe, after
# Okabe and Ito) with open markers, a light grid and a framed key.
set linetype 1 lc rgb '#0072B2' lw 2 pt 7 ps 1.1
set linetype 2 lc rgb '#D55E00' lw 2 pt 5 ps 1.1
set linetype 3 lc rgb '#009E73' lw 2 pt 9 ps 1.3
set linetype 4 lc rgb '#CC79A7' lw 2 pt 11 ps 1.3
set linetype 5 lc rgb '#E69F00' lw 2 pt 13 ps 1.3
set linetype 6 lc rgb '#56B4E9' lw 2 pt 15 ps 1.3
set linetype 7 lc rgb '#000000' lw 2 pt 4 ps 1.1
set linetype 8 lc rgb '#F0E442' lw 2 pt 6 ps 1.1
set linetype cycle 8
set grid lc rgb '#dddddd' lt 1 lw 1
set key box lc rgb '#aaaaaa' opaque
set border lw 1.2
set tics out nomirror
set datafile missing NaN
# Tension cracks in red, shear cracks in blue, everywhere.
tension_colour = '#D62728'
shear_colour = '#1F4E9E'
# Headroom above the highest point when the y range is autoscaled.
set offsets 0, 0, graph 0.06, 0
