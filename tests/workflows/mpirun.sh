#!/bin/sh
# The workflows run solve under a launcher (MPIRUN): a case on two ranks
# gives the bits of one process; Ctrl-C (SIGINT to make's process group,
# mpirun's, before step 700: DEM_TEST_INTERRUPT in solve/run.c; mpirun
# passes it on to the ranks as SIGTERM) makes mpirun exit 1, not solve's 3,
# and the run is still taken as interrupted (its report says so): its
# recovery copy run.h5.ckpt, no run.failed.h5; the same make command
# continues it on two ranks, to the bits of the run not interrupted.
# Usage: mpirun.sh BIN_DIR SOURCE_DIR TMP_DIR MPIEXEC
set -eu
bin=$1 src=$2 tmp=$3 mpiexec=$4
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
# mpirun passes SIGINT on as SIGTERM after 1 s (not the workflows' 30).
export OMPI_MCA_odls_base_sigkill_timeout=1
rm -rf "$tmp"
. "$src/tests/workflows/small_share.sh"
small_share "$tmp" 0.01 a

fail() { echo "FAIL: $*" >&2; exit 1; }
launch="$mpiexec -np 2 --oversubscribe"
run() { # make's arguments
	make -C "$src/workflows" BIN="$bin" SHARE="$tmp/share" OUT="$tmp/runs" THREADS=1 \
		CASES=a a.specimen=small "$@" "$tmp/runs/a/run.h5"
}
same() { /usr/bin/python3 "$src/tests/solve/same_run.py" "$tmp/whole.h5" "$tmp/runs/a/run.h5" > /dev/null; }

# One process, then two ranks: the same run.
run > "$tmp/log" 2>&1 || { cat "$tmp/log" >&2; fail "make, one process"; }
mv "$tmp/runs/a/run.h5" "$tmp/whole.h5"
run MPIRUN="$launch" > "$tmp/log" 2>&1 || { cat "$tmp/log" >&2; fail "make MPIRUN='$launch'"; }
grep -q "^$launch $bin/solve" "$tmp/log" || { cat "$tmp/log" >&2; fail "solve not run by $launch"; }
same || fail "the run on two ranks differs from the one on one process"

# Interrupted: make fails, the run is kept as its recovery copy.
rm "$tmp/runs/a/run.h5"
if DEM_TEST_INTERRUPT=700 setsid --wait make -C "$src/workflows" BIN="$bin" SHARE="$tmp/share" \
	OUT="$tmp/runs" THREADS=1 CASES=a a.specimen=small MPIRUN="$launch" "$tmp/runs/a/run.h5" \
	> "$tmp/log" 2>&1; then
	fail "make, interrupted: succeeded"
fi
grep -q "interrupted at step [0-9]* (Terminated)" "$tmp/log" ||
	{ cat "$tmp/log" >&2; fail "solve not interrupted by mpirun"; }
[ ! -e "$tmp/runs/a/run.h5" ] || fail "an interrupted run left runs/a/run.h5"
[ ! -e "$tmp/runs/a/run.failed.h5" ] || { cat "$tmp/log" >&2; fail "an interrupted run taken as failed"; }
[ -s "$tmp/runs/a/run.h5.ckpt" ] || fail "an interrupted run left no recovery copy"
run MPIRUN="$launch" > "$tmp/log" 2>&1 || { cat "$tmp/log" >&2; fail "make, continued"; }
grep -q "did not finish; continuing it" "$tmp/log" || { cat "$tmp/log" >&2; fail "not continued"; }
same || fail "the continued run differs from the whole one"
rm -rf "$tmp"
echo "workflows under mpirun: the bits of one process, an interruption continued"
