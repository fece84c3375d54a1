# The stress-strain curves of every run of a parametric study overlaid:
# one colour per point of the parameters, the repeats over packing seeds in
# the same colour.
# Drawn by `post study --table`, which defines:
#   $curves  one dataset (index) per run: axial strain(%) axial stress(MPa)
#            (the splitting tensile stress 2P/(π D t) of Brazilian tests)
#   ncurves, curve_lt[k] (its line type), curve_title[k] ('' for no entry
#   in the key), title_text, tensile (1: Brazilian tests)
set title title_text noenhanced
set xlabel 'axial strain ε_a (%)'
if (tensile) {
    set ylabel 'splitting tensile stress σ_t = 2P/(π D t) (MPa)'
} else {
    set ylabel 'axial stress σ_a (MPa)'
}
set yrange [0:*]
set key bottom right noenhanced font ',9'
plot for [k=1:ncurves] $curves index k-1 using 1:2 with lines lt curve_lt[k] \
     title curve_title[k]
