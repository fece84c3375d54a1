#!/bin/sh
# Every rank of a run makes the same collective MPI calls in the same
# order, with frequent writes of the run file they share: a history row
# every 2 steps (rank 0 alone holds the rows: a collective write where the
# others select none), snapshots, checkpoints (rank 0's datasets and each
# rank's rows), cracks in small rounds. Without h5_settle (lib/h5.h) this
# run stopped for good in its first seconds: HDF5's metadata cache ran a
# sync point, held back since the previous write, inside rank 0's chunk
# look-ups alone, rank 0 in its barrier and rank 1 in the write's
# reduction (share/doc/solve.md, "Several machines"). The calls are
# logged by the preloaded library COLLECTIVES (collectives.c).
# Usage: ranks_collectives.sh BIN_DIR TMP_DIR MPIEXEC COLLECTIVES
set -eu
bin=$1 tmp=$2 mpiexec=$3 lib=$4
here=$(cd "$(dirname "$0")" && pwd)
. "$here/ranks_common.sh"
"$bin/pack" --quiet --diameter 0.011 --height 0.022 --radius 0.0005 --dist fuzz --fuzz 0.3 a.h5
cat > ucs.json <<JSON
{"test": "ucs", "assembly": "a.h5", "material": "$share/materials/cement.json",
 "damping": {"translational": 0.1, "rotational": 0.1},
 "output": {"history_every": 2, "snapshot_every": 25, "checkpoint_every": 100},
 "loading": [{"axial": {"mode": "strain_rate", "rate": 120.0}}],
 "stop": {"strain_axial": 0.03, "stress_drop": 0.7}}
JSON
# The run; stalled when no rank has made a collective call for 30 s (it
# makes several a step). A sanitizer's runtime would otherwise insist on
# being loaded first.
DEM_TEST_CRACK_ROWS=16 "$mpiexec" --oversubscribe -np 2 -x LD_PRELOAD="$lib" \
	-x DEM_COLLECTIVES="$tmp/calls" -x ASAN_OPTIONS=verify_asan_link_order=0 \
	"$bin/solve" --quiet --threads 1 --max-steps 1000 --output run.h5 ucs.json &
pid=$!
last= still=0
while kill -0 $pid 2> /dev/null && [ $still -lt 30 ]; do
	sleep 1
	now=$(cat calls.* 2> /dev/null | wc -l)
	if [ "$now" = "$last" ]; then still=$((still + 1)); else still=0; fi
	last=$now
done
stalled=0
if kill -0 $pid 2> /dev/null; then
	stalled=1
	kill $pid
	sleep 2
	kill -9 $pid 2> /dev/null || true
fi
rc=0
wait $pid || rc=$?
# The calls made; the callers' names are left out (ranks of another build
# may name them otherwise).
for r in 0 1; do
	[ -s "calls.$r" ] || { echo "no collective calls logged by rank $r" >&2; exit 1; }
	cut -d' ' -f1-4 "calls.$r" > "seq.$r"
done
if ! cmp -s seq.0 seq.1 || [ $stalled = 1 ] || [ $rc -ne 3 ]; then
	if [ $stalled = 1 ]; then
		echo "the run stalled: no collective call for 30 s" >&2
	elif [ $rc -ne 3 ]; then
		echo "the run ended with status $rc (expected 3: --max-steps)" >&2
	fi
	line=$(cmp seq.0 seq.1 | sed -n 's/.* line \([0-9]*\)$/\1/p')
	if [ -n "$line" ]; then
		echo "the ranks' collective calls differ at call $line (call, communicator," \
			"count, root, caller):" >&2
		for r in 0 1; do
			echo "rank $r:" >&2
			sed -n "$((line > 3 ? line - 3 : 1)),$((line + 1))p" "calls.$r" >&2
		done
	fi
	exit 1
fi
echo "both ranks made the same $(wc -l < seq.0) collective calls"
