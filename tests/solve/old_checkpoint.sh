#!/bin/sh
# Checkpoints written before the laws kept a constant of each bond (jcfpm:
# k_n in h[2], 0 before; exponential: C_n in h[1], which held d_s; onate:
# C_n in the record's k, which no checkpoint holds) continue to the end as
# this build runs the whole case, bit for bit: the law sets the constant
# again after reading them (law.restore). They also hold the bond
# forces in double precision, which this build keeps (for the output only)
# in single precision, so each stops before its first crack or snapshot,
# whose forces the build before wrote in double precision. data/old-LAW.h5:
# the case below, made with a build before and interrupted at step STOP
# (jcfpm and exponential: ac765f5; onate: 0729df6). Their particles are in
# the Morton order alone, without the walk within cells (solve/order.h),
# which the restart takes from the checkpoint (no `order_walk` attribute)
# and the whole run from DEM_TEST_PLAIN_ORDER.
# Usage: old_checkpoint.sh BIN_DIR TMP_DIR [--make OLD_BIN_DIR]  (--make: write
# the data files with that build instead)
set -eu
bin=$1 tmp=$2 make=
[ "${3:-}" = --make ] && make=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$tmp"
mkdir -p "$tmp"
cd "$tmp"
"$bin/lattice-assembly" --spheres 150 a.h5 > /dev/null

# continues LAW RATE STOP MATERIAL_KEYS
continues() {
	cat > "$1.json" <<JSON
{"assembly": "a.h5",
 "material": {"name": "m", "law": "$1", "density": 2500, $4},
 "loading": [{"axial": {"mode": "strain_rate", "rate": $2}}],
 "output": {"history_every": 100, "snapshot_every": 1000},
 "stop": {"steps": 3000}}
JSON
	if [ -n "$make" ]; then
		"$make/solve" --quiet --threads 1 --max-steps "$3" --output "$here/data/old-$1.h5" \
			"$1.json" || [ $? -eq 3 ]
		return
	fi
	DEM_TEST_PLAIN_ORDER=1 "$bin/solve" --quiet --threads 1 --output "whole-$1.h5" "$1.json"
	cp "$here/data/old-$1.h5" "old-$1.h5"
	"$bin/solve" --quiet --restart "old-$1.h5"
	/usr/bin/python3 "$here/same_run.py" "whole-$1.h5" "old-$1.h5"
}

continues jcfpm 20 150 '"E": 17e9, "ks_ratio": 0.15, "tensile_strength": 3e6,
 "cohesion": 9e6, "friction_angle_deg": 34.25, "interaction_range": 1.4'
continues exponential 60 400 '"E0": 28e9, "nu": 0.2, "tensile_strength": 10e6,
 "delta_n": 0.2, "cohesion": 13e6, "friction_angle_deg": 30,
 "contact_friction_angle_deg": 30, "interaction_range": 1.1, "xi": 0.9'
continues onate 60 900 '"E0": 3.8e9, "nu": 0.2, "tensile_strength": 4.8e6,
 "shear_strength": 8.5e6, "mu1": 0.3, "mu2": 0.4, "LCS1": 8.5e6, "LCS2": 9e6,
 "LCS3": 11e6, "YRC1": 3, "YRC2": 9, "YRC3": 24, "delta_n": 0.2, "delta_s": 0.2,
 "alpha": 1.0'
