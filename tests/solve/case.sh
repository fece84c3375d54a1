# Sourced by the command-line tests of solve: a lattice assembly and a case
# file loading it at a strain rate, linear bonds of a 10 GPa material.
# lattice N: the assembly $tmp/a.h5 of about N spheres.
lattice() {
	"$bin/lattice-assembly" --spheres "$1" "$tmp/a.h5" > /dev/null
}
# case_file FILE KEYS [RATE [STRENGTH]]: the case with KEYS (its "stop" and
# any others, JSON members), the strain rate RATE (1/s, default 1) and the
# bonds' tensile strength STRENGTH (Pa, twice that in shear; default 1e12,
# elastic).
case_file() {
	s=${4:-1e12}
	cat > "$1" <<JSON
{"assembly": "$tmp/a.h5",
 "material": {"name": "m", "law": "linear", "density": 2500, "E": 1e10, "nu": 0.2,
              "tensile_strength": $s, "shear_strength": $(awk "BEGIN {print 2 * $s}")},
 "loading": [{"axial": {"mode": "strain_rate", "rate": ${3:-1}}}],
 $2}
JSON
}
