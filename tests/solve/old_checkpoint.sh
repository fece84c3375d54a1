#!/bin/sh
# A checkpoint written before the jcfpm law kept each bond's k_n in its
# history (h[2] then 0: data/jcfpm-before-kn.h5, the case below interrupted
# at step 800) continues to the end as this build runs the whole case, bit
# for bit: the law sets k_n again after reading it (law.restore).
# Usage: old_checkpoint.sh BIN_DIR TMP_DIR
set -eu
bin=$1 tmp=$2
here=$(dirname "$0")
rm -rf "$tmp"
mkdir -p "$tmp"
cd "$tmp"
"$bin/lattice-assembly" --spheres 150 a.h5 > /dev/null
cat > case.json <<'JSON'
{"assembly": "a.h5",
 "material": {"name": "m", "law": "jcfpm", "density": 2500, "E": 17e9, "ks_ratio": 0.15,
              "tensile_strength": 3e6, "cohesion": 9e6, "friction_angle_deg": 34.25,
              "interaction_range": 1.4},
 "loading": [{"axial": {"mode": "strain_rate", "rate": 20}}],
 "output": {"history_every": 100},
 "stop": {"steps": 3000}}
JSON
"$bin/solve" --quiet --threads 1 --output whole.h5 case.json
cp "$here/data/jcfpm-before-kn.h5" old.h5
"$bin/solve" --quiet --restart old.h5
/usr/bin/python3 "$here/same_run.py" whole.h5 old.h5
