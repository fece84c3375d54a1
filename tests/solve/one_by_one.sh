#!/bin/sh
# The particles' vector form (solve/step.c, integrate_lanes: the particles
# that move freely, those at a platen among them, moved together) gives the
# same bits as moving every particle by itself (integrate_one, which
# DEM_TEST_ONE_BY_ONE=1 makes the engine use throughout): the positions,
# the sums of each step (energies, platen loads, the stress of the measured
# steps) and the cracks, under each kind of lateral load and of axial one
# (platens, end layers), with failing
# bonds and contacts (a lattice jittered enough to leave neighbours
# unbonded).
# Usage: one_by_one.sh BIN_DIR TMP_DIR
set -eu
bin=$1 tmp=$2
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$tmp"
mkdir -p "$tmp"
"$bin/lattice-assembly" --spheres 1500 --jitter 0.2 "$tmp/a.h5" >/dev/null
# loaded KEY LOADING: a case of failing bonds under LOADING, measured
# every 20 steps.
loaded() {
	cat > "$tmp/$1.json" <<JSON
{"assembly": "$tmp/a.h5",
 "material": {"name": "m", "law": "linear", "density": 2500, "E": 1e10, "nu": 0.2,
              "tensile_strength": 2e6, "shear_strength": 4e6},
 "output": {"history_every": 20},
 "loading": [$2],
 "stop": {"steps": 400}}
JSON
}
loaded platens '{"axial": {"mode": "strain_rate", "rate": 400}}'
loaded pressure '{"axial": {"mode": "strain_rate", "rate": 400},
                  "lateral": {"mode": "pressure", "pressure": 2e6}}'
loaded constraint '{"axial": {"mode": "layers", "move": "top", "rate": 400},
                    "lateral": {"mode": "constraint"}}'
loaded layers '{"axial": {"mode": "layers", "move": "both", "rate": 400},
                "lateral": {"mode": "pressure", "pressure": 2e6}}'
for c in platens pressure constraint layers; do
	"$bin/solve" --quiet --threads 2 --output "$tmp/$c.h5" "$tmp/$c.json"
	DEM_TEST_ONE_BY_ONE=1 "$bin/solve" --quiet --threads 2 --output "$tmp/$c-one.h5" \
		"$tmp/$c.json"
	/usr/bin/python3 "$here/same_run.py" "$tmp/$c.h5" "$tmp/$c-one.h5"
done
echo "the particles moved together and one by one: the same runs"
