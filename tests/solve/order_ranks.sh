#!/bin/sh
# The order of test_order's point sets (Morton, walked within cells) on 1,
# 2, 3 and 7 ranks: every rank passes its checks, and the order is the same
# (solve/order.h).
# Usage: order_ranks.sh TEST_PROGRAM TMP_DIR MPIEXEC
set -eu
prog=$1 tmp=$2 mpiexec=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
rm -rf "$tmp"
mkdir -p "$tmp"
for np in 1 2 3 7; do
	"$mpiexec" -np $np --oversubscribe "$prog" >"$tmp/out$np"
	grep '^order ' "$tmp/out$np" >"$tmp/order$np"
done
[ "$(wc -l <"$tmp/order1")" -eq 5 ] || { echo "expected 5 orders"; exit 1; }
for np in 2 3 7; do
	cmp "$tmp/order1" "$tmp/order$np"
done
echo "5 orders, the same on 1, 2, 3 and 7 ranks"
