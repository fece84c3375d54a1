#!/bin/sh
# A run on several ranks (mpirun) is the run on one, bit for bit, whatever
# the threads inside each rank, and a run interrupted on K ranks continues
# on K' (share/doc/solve.md, "Several machines"): a UCS of the paper's
# cement to its stress drop (end layers, cracks, snapshots, checkpoints)
# and a triaxial start (platens, the confining pressure on tributary
# areas). same_run.py compares every dataset and attribute but the
# creation time and the wall-clock rate.
# Usage: ranks.sh BIN_DIR TMP_DIR MPIEXEC
set -eu
bin=$1 tmp=$2 mpiexec=$3
here=$(cd "$(dirname "$0")" && pwd)
share=$(cd "$here/../../share" && pwd)
# Ranks that wait yield the cores to the others (more ranks than cores).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
rm -rf "$tmp"
mkdir -p "$tmp"
cd "$tmp"
same() { /usr/bin/python3 "$here/same_run.py" "$1" "$2"; }
# ranks K ARGS...: solve on K ranks; a run stopped by --max-steps is fine.
ranks() {
	k=$1
	shift
	"$mpiexec" -np "$k" --oversubscribe "$bin/solve" --quiet "$@" || [ $? -eq 3 ]
}
# About 2 400 spheres: 10 blocks of 256, two threads' shares on a rank.
"$bin/pack" --quiet --diameter 0.011 --height 0.022 --radius 0.0005 --dist fuzz --fuzz 0.3 a.h5
cat > ucs.json <<JSON
{"test": "ucs", "assembly": "a.h5", "material": "$share/materials/cement.json",
 "damping": {"translational": 0.1, "rotational": 0.1},
 "output": {"history_every": 50, "snapshot_every": 250, "checkpoint_every": 400},
 "loading": [{"axial": {"mode": "strain_rate", "rate": 120.0}}],
 "stop": {"strain_axial": 0.03, "stress_drop": 0.7}}
JSON
"$bin/solve" --quiet --threads 1 --output ucs1.h5 ucs.json
# The run to compare breaks bonds and ends by its stress-drop rule.
/usr/bin/python3 -c '
import sys, h5py
f = h5py.File("ucs1.h5", "r")
ok = f["cracks/i"].shape[0] > 100 and b"stress fell" in f.attrs["status"]
sys.exit(0 if ok else "ucs1.h5: expected cracks and the stress-drop stop")'
ranks 2 --threads 2 --output ucs2.h5 ucs.json
same ucs1.h5 ucs2.h5
ranks 3 --threads 1 --max-steps 800 --output ucs3.h5 ucs.json
ranks 2 --threads 1 --restart ucs3.h5
same ucs1.h5 ucs3.h5
cat > tri.json <<JSON
{"test": "triaxial", "assembly": "a.h5", "material": "$share/materials/cement-500psi.json",
 "damping": {"translational": 0.1, "rotational": 0.1},
 "output": {"history_every": 50, "snapshot_every": 400},
 "loading": [{"ramp": 0.0002,
              "axial": {"mode": "stress", "stress": 3447379, "rate": 20.0},
              "lateral": {"mode": "pressure", "pressure": 3447379, "method": "tributary"}}],
 "stop": {"steps": 800}}
JSON
"$bin/solve" --quiet --threads 1 --output tri1.h5 tri.json
ranks 2 --threads 1 --output tri2.h5 tri.json
same tri1.h5 tri2.h5
