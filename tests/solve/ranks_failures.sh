#!/bin/sh
# Failures of a run on several ranks (share/doc/solve.md, "Several
# machines"): a restart file of another format version gives one message
# and a non-zero exit on 2 ranks, and leaves the file as it was; so does
# an output directory or a restart file that is not the same on every
# rank, where the MPI-IO open waited forever; runs
# stopped by a diagnosis (a runaway, a non-finite state) on 3 ranks are
# the runs on one, message and all; the recovery copy of a step on 2
# ranks is that of one process; a rank killed with SIGKILL ends the run
# (the other rank does not wait forever) without a finished-looking run
# file, and the run then continues from its recovery copy, on 3 ranks by
# the same command and on 2 by --restart, to the same bits as the
# uninterrupted run of one process.
# Usage: ranks_failures.sh BIN_DIR TMP_DIR MPIEXEC
set -eu
bin=$1 tmp=$2 mpiexec=$3
here=$(cd "$(dirname "$0")" && pwd)
. "$here/ranks_common.sh"
# Stale particles of other ranks are NaN: a read that misses a gather shows.
export DEM_RANKS_POISON=1
fail() {
	echo "$*" >&2
	exit 1
}
ucs_case 100
"$bin/solve" --quiet --threads 1 --output ref.h5 ucs.json

# A restart file of another version: one message, status 1, the file kept.
"$mpiexec" -np 2 --oversubscribe "$bin/solve" --quiet --max-steps 300 --output s.h5 ucs.json ||
	[ $? -eq 3 ] || fail "2 ranks, --max-steps 300: expected status 3"
/usr/bin/python3 -c '
import h5py
with h5py.File("s.h5", "r+") as f:
    f.attrs["format_version"] = 99'
sum0=$(cksum < s.h5)
if "$mpiexec" -np 2 --oversubscribe "$bin/solve" --quiet --restart s.h5 2> bad.err; then
	fail "restart of a format_version 99 file on 2 ranks: expected a failure"
fi
n=$(grep -c "^solve.*s.h5: attribute 'format_version': value 99: expected 1 to 3" bad.err || true)
[ "$n" -eq 1 ] || { cat bad.err >&2; fail "expected the version message once, got $n"; }
[ "$(cksum < s.h5)" = "$sum0" ] || fail "s.h5 changed by a refused restart"

# An output directory that is not one directory on every rank (here each
# rank's own working directory, as a directory local to each machine
# would be): one message and status 1, nothing left behind, where Open
# MPI's MPI-IO open of the run file waited forever; the same for a
# restart from a copy of a run file.
sed "s|\"a.h5\"|\"$PWD/a.h5\"|" ucs.json > abs.json
mkdir -p here/out there/out
on_two() { # the same solve arguments on a rank in here/ and one in there/
	timeout 120 "$mpiexec" --oversubscribe -np 1 -wdir "$PWD/here" "$bin/solve" --quiet \
		--threads 1 "$@" : -np 1 -wdir "$PWD/there" "$bin/solve" --quiet --threads 1 "$@"
}
expect_local() { # status, err file, what
	[ "$1" -eq 1 ] || { cat "$2" >&2; fail "$3: expected status 1, got $1"; }
	n=$(grep -c "^solve.*out/[a-z]*.h5: not the same file on every rank (1 of the 2 ranks" "$2" || true)
	[ "$n" -eq 1 ] || { cat "$2" >&2; fail "$3: expected the message once, got $n"; }
}
status=0
on_two --output out/run.h5 "$PWD/abs.json" 2> local.err || status=$?
expect_local "$status" local.err "a local output directory"
left=$(find here/out there/out -type f)
[ -z "$left" ] || fail "a local output directory: files left: $left"
(cd here && "$bin/solve" --quiet --threads 1 --max-steps 100 --output out/int.h5 "$PWD/../abs.json") ||
	[ $? -eq 3 ] || fail "1 process, --max-steps 100: expected status 3"
cp here/out/int.h5 there/out/int.h5
touch -d 2000-01-01 there/out/int.h5 # a copy, whatever the clock's resolution
sum0=$(cksum < here/out/int.h5)
status=0
on_two --restart out/int.h5 2> copy.err || status=$?
expect_local "$status" copy.err "a restart from a copy"
[ "$(cksum < here/out/int.h5)" = "$sum0" ] || fail "a restart from a copy: the run file changed"

# The diagnoses read each rank's own particles: a run that one stops (a
# skin so thin that the first step moves particles across half of it) on
# 3 ranks is the run on one, its message included.
sed 's/"damping"/"neighbours": {"skin": 1e-12}, "damping"/' ucs.json > thin.json
if "$bin/solve" --quiet --threads 1 --output thin1.h5 thin.json 2> thin.err; then
	fail "a skin of 1e-12 m: expected the run to stop"
fi
grep -q "moved .* in one step" thin.err || { cat thin.err >&2; fail "expected the speed diagnosis"; }
if "$mpiexec" -np 3 --oversubscribe "$bin/solve" --quiet --threads 1 --output thin3.h5 \
	thin.json 2> thin.err; then
	fail "a skin of 1e-12 m on 3 ranks: expected the run to stop"
fi
same thin1.h5 thin3.h5

# The diagnosis of a non-finite state shares only the pairs whose forces
# are not finite: a velocity made NaN (DEM_TEST_NAN, solve/run.c) stops
# the run on 3 ranks as on one, its message naming the same particle and
# bond.
if DEM_TEST_NAN=700 "$bin/solve" --quiet --threads 1 --output nan1.h5 ucs.json 2> nan.err; then
	fail "a NaN velocity: expected the run to stop"
fi
grep -q "non-finite state at step .*: particle 700 .* bonds have non-finite forces" nan.err ||
	{ cat nan.err >&2; fail "expected the non-finite diagnosis"; }
if DEM_TEST_NAN=700 "$mpiexec" -np 3 --oversubscribe "$bin/solve" --quiet --threads 1 \
	--output nan3.h5 ucs.json 2> nan3.err; then
	fail "a NaN velocity on 3 ranks: expected the run to stop"
fi
same nan1.h5 nan3.h5

# The recovery copy of a checkpoint at which a dataset that rank 0 alone
# writes (the surface list) is shorter than at the checkpoint before holds
# the run of one process at that step: every process kills itself right
# after the copy of step 300 (DEM_TEST_KILL, solve/run.c), on one process
# and on 2 ranks, and the two copies are compared.
killed_at() {
	k=$1
	shift
	if DEM_TEST_KILL=$k "$@" 2> killed.err; then
		fail "DEM_TEST_KILL=$k $*: expected the run to be killed"
	fi
}
killed_at 200 "$bin/solve" --quiet --threads 1 --output c200.h5 ucs.json
killed_at 300 "$bin/solve" --quiet --threads 1 --output c1.h5 ucs.json
/usr/bin/python3 -c '
import sys, h5py
n = [h5py.File(p, "r")["checkpoint/surface_area"].shape[0] for p in sys.argv[1:]]
if not n[1] < n[0]:
    sys.exit("surface list of %d particles at step 200, %d at 300: expected it shorter" % tuple(n))' \
	c200.h5.ckpt c1.h5.ckpt
killed_at 300 "$mpiexec" -np 2 --oversubscribe "$bin/solve" --quiet --output c2.h5 ucs.json
same c1.h5.ckpt c2.h5.ckpt

# A rank killed with SIGKILL after the first checkpoint.
"$mpiexec" -np 2 --oversubscribe "$bin/solve" --quiet --output k.h5 ucs.json 2> kill.err &
job=$!
i=0
while [ ! -e k.h5.ckpt ]; do
	i=$((i + 1))
	[ $i -lt 6000 ] || fail "no recovery copy k.h5.ckpt after 600 s"
	sleep 0.1
done
victim=$(pgrep -f -- "--output k.h5 ucs.json" | grep -vx "$job" | tail -n 1)
kill -9 "$victim"
if wait "$job"; then
	fail "a rank killed: expected the run to fail"
fi
[ ! -e k.h5 ] || fail "a rank killed: k.h5 looks finished"
# The same command again, here on 3 ranks, finds the recovery copy of a
# run of the same case on the same assembly (each rank comparing its piece
# of it) and continues it.
cp k.h5.ckpt k3.h5.ckpt
"$mpiexec" -np 3 --oversubscribe "$bin/solve" --threads 1 --output k3.h5 ucs.json 2> again.err
grep -q "a run of this case did not finish; continuing it" again.err ||
	{ cat again.err >&2; fail "3 ranks, the same command: expected it to continue the run"; }
same ref.h5 k3.h5
"$mpiexec" -np 2 --oversubscribe "$bin/solve" --quiet --restart k.h5
same ref.h5 k.h5
