# Sourced by make.sh and mpirun.sh: small_share DIR STRAIN CASE... makes
# DIR/share, a SHARE for the workflows with the specimen "small" (a
# cylinder of some 500 spheres), the material m.json (linear law) and, for
# each CASE, cases/CASE.json: a UCS on it stopping at axial strain STRAIN.
small_share() {
	dir=$1 strain=$2
	shift 2
	mkdir -p "$dir/share/specimens" "$dir/share/cases" "$dir/share/materials"
	cat > "$dir/share/specimens/small.json" <<'JSON'
{"shape": "cylinder", "diameter": 0.012, "height": 0.024, "rmin": 0.0006, "rmax": 0.0012}
JSON
	cat > "$dir/share/materials/m.json" <<'JSON'
{"name": "m", "law": "linear", "density": 1700, "E": 10e9, "nu": 0.2,
 "tensile_strength": 5e6, "shear_strength": 10e6, "mu2": 0.5, "contact": {"friction": 0.5}}
JSON
	for c in "$@"; do
		cat > "$dir/share/cases/$c.json" <<JSON
{"test": "ucs", "assembly": "assembly.h5", "material": "../materials/m.json",
 "damping": {"translational": 0.1, "rotational": 0.1},
 "loading": [{"name": "axial", "axial": {"mode": "strain_rate", "rate": 5.0}}],
 "stop": {"strain_axial": $strain}}
JSON
	done
}
