# Energies against axial strain, one line per energy_* history column.
# Drawn by `post curve`, which defines:
#   $energy   rows: axial strain(%) then one column per energy (J)
#   nenergy;  ename[k]  name of energy k (the column without 'energy_')
set title 'Energies'
set xlabel 'axial strain ε_a (%)'
set ylabel 'energy (J)'
set key top left noenhanced
plot for [k=1:nenergy] $energy using 1:(column(k + 1)) with lines lt k title ename[k]
