#!/bin/sh
# The critical time step's bound of test_timestep_ranks on 1, 3 and 7
# ranks: the same 32 lines.
# Usage: timestep_ranks.sh TEST_PROGRAM TMP_DIR MPIEXEC
set -eu
prog=$1 tmp=$2 mpiexec=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
rm -rf "$tmp"
mkdir -p "$tmp"
for np in 1 3 7; do
	"$mpiexec" -np $np --oversubscribe "$prog" >"$tmp/out$np"
	grep '^bound ' "$tmp/out$np" >"$tmp/bound$np"
done
[ "$(wc -l <"$tmp/bound1")" -eq 32 ] || { echo "expected 32 bounds"; exit 1; }
cmp "$tmp/bound1" "$tmp/bound3"
cmp "$tmp/bound1" "$tmp/bound7"
echo "32 bounds, the same on 1, 3 and 7 ranks"
