#!/bin/sh
# A run on several ranks (mpirun) is the run on one, bit for bit, whatever
# the threads inside each rank and however often its cracks are written, and a run interrupted on K ranks continues
# on K' (share/doc/solve.md, "Several machines"): a UCS of the paper's
# cement to its stress drop (end layers, cracks, snapshots, checkpoints)
# on 1 rank, 2 ranks x 2 threads, and 3 ranks continued on 2 and on one
# process; a confined triaxial with an unload-reload cycle on 4 continued
# on 3; a Brazilian test on 7; a larger cylinder whose output datasets
# have several chunks on 3 and 4, where each rank holds only the particles
# it reads.
# same_run.py compares every dataset and attribute but the creation time
# and the wall-clock rate. The runs on several ranks poison the particles
# they do not receive each step (DEM_RANKS_POISON, solve/ranks.h), so a
# read of one shows as a NaN or a difference.
# Usage: ranks.sh BIN_DIR TMP_DIR MPIEXEC
set -eu
bin=$1 tmp=$2 mpiexec=$3
here=$(cd "$(dirname "$0")" && pwd)
. "$here/ranks_common.sh"
# ranks K ARGS...: solve on K ranks; a run stopped by --max-steps is fine.
ranks() {
	k=$1
	shift
	DEM_RANKS_POISON=1 "$mpiexec" -np "$k" --oversubscribe "$bin/solve" --quiet "$@" ||
		[ $? -eq 3 ]
}
ucs_case 400
"$bin/solve" --quiet --threads 1 --output ucs1.h5 ucs.json
# The run to compare breaks bonds and ends by its stress-drop rule.
/usr/bin/python3 -c '
import sys, h5py
f = h5py.File("ucs1.h5", "r")
ok = f["cracks/i"].shape[0] > 100 and b"stress fell" in f.attrs["status"]
sys.exit(0 if ok else "ucs1.h5: expected cracks and the stress-drop stop")'
# Its cracks written whenever a rank holds 16 of them: in many rounds, each
# rank's rows at their places.
DEM_TEST_CRACK_ROWS=16 ranks 2 --threads 2 --output ucs2.h5 ucs.json
same ucs1.h5 ucs2.h5
# One rank under mpirun: MPI started, the run file written as by one
# process.
ranks 1 --threads 2 --output ucs1m.h5 ucs.json
/usr/bin/python3 "$here/same_run.py" --chunks ucs1.h5 ucs1m.h5
ranks 3 --threads 1 --max-steps 800 --output ucs3.h5 ucs.json
cp ucs3.h5 ucs3p.h5
ranks 2 --threads 1 --restart ucs3.h5
same ucs1.h5 ucs3.h5
# And continued by one process, without mpirun.
"$bin/solve" --quiet --threads 2 --restart ucs3p.h5
same ucs1.h5 ucs3p.h5
# A confined triaxial with an unload-reload cycle (hydrostatic ramp on the
# platens, confinement on tributary areas, then the end layers) on 4 ranks;
# its stages change between the surface updates (every 100 steps), where
# only the halo is current.
cat > tri.json <<JSON
{"test": "triaxial", "assembly": "a.h5", "material": "$share/materials/cement-500psi.json",
 "damping": {"translational": 0.1, "rotational": 0.1},
 "output": {"history_every": 50, "snapshot_every": 400},
 "loading": [
  {"name": "hydrostatic", "ramp": 0.0001,
   "axial": {"mode": "stress", "stress": 3447379, "rate": 20.0},
   "lateral": {"mode": "pressure", "pressure": 3447379, "method": "tributary"},
   "until": {"steps": 470}},
  {"name": "load", "axial": {"mode": "layers", "move": "top", "rate": 60.0},
   "lateral": {"mode": "pressure", "pressure": 3447379, "method": "tributary"},
   "until": {"steps": 530}},
  {"name": "unload", "axial": {"mode": "layers", "move": "top", "rate": -60.0},
   "lateral": {"mode": "pressure", "pressure": 3447379, "method": "tributary"},
   "until": {"steps": 230}},
  {"name": "reload", "axial": {"mode": "layers", "move": "top", "rate": 60.0},
   "lateral": {"mode": "pressure", "pressure": 3447379, "method": "tributary"}}],
 "stop": {"steps": 1500}}
JSON
"$bin/solve" --quiet --threads 1 --output tri1.h5 tri.json
# Interrupted in its loading stage, after the end layers were chosen, and
# continued on 3 ranks.
ranks 4 --threads 1 --max-steps 700 --output tri4.h5 tri.json
ranks 3 --threads 1 --restart tri4.h5
same tri1.h5 tri4.h5
# A Brazilian test (a disc of about 1 700 spheres between platens, to
# its first cracks) on 7 ranks.
"$bin/pack" --quiet --shape disc --diameter 0.016 --thickness 0.008 --radius 0.0005 \
	--dist fuzz --fuzz 0.3 disc.h5
cat > bts.json <<JSON
{"test": "bts", "assembly": "disc.h5", "material": "$share/materials/cement.json",
 "damping": {"translational": 0.1, "rotational": 0.1},
 "output": {"history_every": 50, "snapshot_every": 200},
 "loading": [{"axial": {"mode": "strain_rate", "rate": 200.0}}], "axis": [1, 0, 0],
 "stop": {"steps": 800}}
JSON
"$bin/solve" --quiet --threads 1 --output bts1.h5 bts.json
ranks 7 --threads 1 --output bts7.h5 bts.json
same bts1.h5 bts7.h5
# Datasets of several chunks, which each rank compresses where the rows
# are (ranks_rows_write): 26 000 spheres, 3 ranks x 2 threads; the bond
# table and snapshots must be stored chunk for chunk as one process stores
# them. On 4 ranks, a chunk a rank in each round (DEM_ROWS_ROUND=1), so
# that a dataset takes several rounds and a rank has none in some.
"$bin/lattice-assembly" --spheres 26000 --radius 0.0005 lat.h5 >/dev/null
cat > lat.json <<JSON
{"test": "ucs", "assembly": "lat.h5", "material": "$share/materials/cement.json",
 "output": {"history_every": 10, "snapshot_every": 10},
 "loading": [{"axial": {"mode": "strain_rate", "rate": 1.0}}], "stop": {"steps": 20}}
JSON
"$bin/solve" --quiet --threads 1 --output lat1.h5 lat.json
ranks 3 --threads 2 --output lat3.h5 lat.json
same_chunks() { /usr/bin/python3 "$here/same_run.py" --chunks "$1" "$2"; }
same_chunks lat1.h5 lat3.h5
DEM_ROWS_ROUND=1 ranks 4 --threads 1 --output lat4.h5 lat.json --report lat4.json
same_chunks lat1.h5 lat4.h5
# Each rank holds its own particles and those it reads of the others (its
# window, solve/window.h), not the whole specimen: on 4 ranks, well under
# half of it each, at the end and at any time, setup included (each rank
# reads a piece of the assembly, solve/order.h), and likewise when the run
# continues from a checkpoint on 4 ranks.
ranks 4 --threads 1 --max-steps 10 --output lat4r.h5 lat.json
ranks 4 --threads 1 --restart lat4r.h5 --report lat4r.json
same_chunks lat1.h5 lat4r.h5
windows() {
	/usr/bin/python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))
n = r["particles"]
for k in ("rank_particles_held_max", "rank_particles_held_peak_max"):
    if not n / 4 < r[k] < 0.45 * n:
        sys.exit("%s: %s %g of %g particles: expected its window" % (sys.argv[1], k, r[k], n))' "$1"
}
windows lat4.json
windows lat4r.json
# More ranks than the specimen has blocks of particles: one clear message
# on each rank, a failed run, no run file.
"$bin/pack" --quiet --diameter 0.006 --height 0.012 --radius 0.0005 --dist fuzz small.h5
sed 's/"a.h5"/"small.h5"/' ucs.json > small.json
if "$mpiexec" -np 3 --oversubscribe "$bin/solve" --quiet --output small.h5.run small.json \
	2> small.err; then
	echo "3 ranks on 2 blocks: expected a failure" >&2
	exit 1
fi
grep -q "3 ranks for [0-9]* particles: a rank takes whole blocks of 256 particles, so this specimen runs on at most 2 ranks" small.err
[ ! -e small.h5.run ]
