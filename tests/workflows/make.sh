#!/bin/sh
# The workflows re-run exactly what changed: nothing when nothing changed;
# solve and post, not pack, when a material file changes; everything when the
# specimen or the seed changes. Runs on the same specimen share one assembly,
# packed once (also under make -j2) and linked from each run's directory. Two
# cases run side by side with make -j2, and a failing solve leaves no run.h5
# that make would take as complete; an interrupted one leaves its recovery
# copy, which make continues. A run may take another case's file and a
# sphere count of its own.
# Usage: make.sh BIN_DIR SOURCE_DIR TMP_DIR
set -eu
bin=$1 src=$2 tmp=$3
rm -rf "$tmp"
. "$src/tests/workflows/small_share.sh"
small_share "$tmp" 0.001 a b
cp "$tmp/share/cases/a.json" "$tmp/share/cases/bad.json"
sed -i 's/"test"/"no_such_key": 1, "test"/' "$tmp/share/cases/bad.json"

fail() { echo "FAIL: $*" >&2; exit 1; }
# The programs a make run started, in order, e.g. "pack solve post post post".
ran() {
	make -C "$src/workflows" BIN="$bin" SHARE="$tmp/share" OUT="$tmp/runs" THREADS=1 \
		CASES="a b bad c" a.specimen=small b.specimen=small bad.specimen=small \
		c.specimen=small c.case=a c.count=300 "$@" \
		> "$tmp/log" 2>&1 || return 1
	grep -o "^$bin/[a-z]*" "$tmp/log" | sed "s|^$bin/||" | tr '\n' ' ' | sed 's/ $//'
}
expect() { # expected-programs make-arguments...
	want=$1
	shift
	got=$(ran "$@") || { cat "$tmp/log" >&2; fail "make $* failed"; }
	[ "$got" = "$want" ] || { cat "$tmp/log" >&2; fail "make $*: ran '$got', expected '$want'"; }
}

# Where run R's assembly.h5 leads, relative to runs/.
assembly_of() { realpath --relative-to="$tmp/runs" "$tmp/runs/$1/assembly.h5"; }

expect "pack solve post post post post" a
for f in assembly.h5 specimen.key run.h5 run.d report.json summary.json curve.csv \
	stress_strain.png cracks.csv vtk/run.pvd; do
	[ -s "$tmp/runs/a/$f" ] || fail "runs/a/$f missing"
done
for f in assembly.h5 assembly.d pack.txt pack.args; do
	[ -s "$tmp/runs/specimens/small/$f" ] || fail "runs/specimens/small/$f missing"
done
[ -L "$tmp/runs/a/assembly.h5" ] || fail "runs/a/assembly.h5 is not a link"
[ "$(assembly_of a)" = specimens/small/assembly.h5 ] || fail "runs/a/assembly.h5 leads to $(assembly_of a)"
expect "" a
expect "" a -n
sleep 1
touch "$tmp/share/materials/m.json"
# A dry run tells the truth: solve and post, not pack.
expect "solve post post post post" a -n
expect "solve post post post post" a
touch "$tmp/share/specimens/small.json"
expect "pack solve post post post post" a
expect "pack solve post post post post" a SEED=7 -n
expect "pack solve post post post post" a SEED=7
expect "" a SEED=7
[ "$(assembly_of a)" = specimens/small.seed-7/assembly.h5 ] || fail "SEED=7: runs/a/assembly.h5 leads to $(assembly_of a)"
# Back to the specimen's own seed: its assembly is still there and current,
# older than a's run; the run's key changed, so solve runs, pack does not.
expect "solve post post post post" a -n
expect "solve post post post post" a
[ "$(assembly_of a)" = specimens/small/assembly.h5 ] || fail "runs/a/assembly.h5 not back on specimens/small"

# Two runs on one specimen: after a clean, a dry run lists one pack, then
# both solves; make -j2 packs it once, both complete, each with its own run.
rm -rf "$tmp/runs"
expect "pack solve post post post post solve post post post post" a b -n
got=$(ran -j2 a b) || { cat "$tmp/log" >&2; fail "make -j2 a b failed"; }
[ "$(echo "$got" | tr ' ' '\n' | grep -c pack)" = 1 ] || fail "make -j2 a b: ran '$got', expected one pack"
[ -s "$tmp/runs/b/vtk/run.pvd" ] || fail "make -j2: runs/b incomplete"
[ "$(assembly_of b)" = specimens/small/assembly.h5 ] || fail "runs/b/assembly.h5 leads to $(assembly_of b)"
ls "$tmp/runs/specimens" | grep -qv '^small$' && fail "more than one specimen packed: $(ls "$tmp/runs/specimens")"
# Both runs depend on it: a changed specimen re-packs it once, and both solve.
sleep 1
touch "$tmp/share/specimens/small.json"
expect "pack solve post post post post solve post post post post" a b -n
expect "pack solve post post post post solve post post post post" a b

# A run of another run's case with a sphere count of its own: a specimen of its own.
expect "pack solve post post post post" c COUNT=900
[ "$(cat "$tmp/runs/c/specimen.key")" = small.count-300 ] || fail "c.count not in c's key"
grep -q -- "--count 300$" "$tmp/runs/specimens/small.count-300/pack.args" || fail "c.count not used"
grep -q "cases/a.json" "$tmp/runs/c/run.d" || fail "c.case not used"

# Ctrl-C during a solve (SIGINT to make's whole process group before step
# 700, DEM_TEST_INTERRUPT in solve/run.c; make in a session of its own)
# fails make and leaves the run as the recovery copy run.h5.ckpt: no run.h5
# that make would take as complete, no run.failed.h5. The same make command
# continues it, to the bits of the run not interrupted.
cp "$tmp/runs/a/run.h5" "$tmp/whole.h5"
sleep 1
touch "$tmp/share/materials/m.json"
if DEM_TEST_INTERRUPT=700 setsid --wait make -C "$src/workflows" \
	BIN="$bin" SHARE="$tmp/share" OUT="$tmp/runs" THREADS=1 CASES="a b bad c" \
	a.specimen=small b.specimen=small bad.specimen=small c.specimen=small a > "$tmp/log" 2>&1; then
	fail "make a, interrupted: succeeded"
fi
grep -q "interrupted at step 701" "$tmp/log" || { cat "$tmp/log" >&2; fail "solve not interrupted"; }
grep -q "; continue with: make -C $src/workflows a .*THREADS=1 " "$tmp/log" ||
	{ cat "$tmp/log" >&2; fail "solve did not say that the make command continues the run"; }
[ ! -e "$tmp/runs/a/run.h5" ] || fail "an interrupted run left runs/a/run.h5"
[ ! -e "$tmp/runs/a/run.failed.h5" ] || fail "an interrupted run taken as failed"
[ -s "$tmp/runs/a/run.h5.ckpt" ] || fail "an interrupted run left no recovery copy"
expect "solve post post post post" a
grep -q "did not finish; continuing it" "$tmp/log" || { cat "$tmp/log" >&2; fail "not continued"; }
/usr/bin/python3 "$src/tests/solve/same_run.py" "$tmp/whole.h5" "$tmp/runs/a/run.h5" > /dev/null ||
	fail "the continued run differs from the whole one"

# An output path with a space: one message naming it, nothing made.
if make -C "$src/workflows" BIN="$bin" OUT="$tmp/with space" a > "$tmp/log" 2>&1; then
	fail "OUT with a space: make succeeded"
fi
grep -q "OUT='$tmp/with space': a path with spaces" "$tmp/log" || { cat "$tmp/log" >&2; fail "no message for OUT with a space"; }
[ ! -e "$tmp/with space" ] || fail "OUT with a space: something was made"

# A case solve rejects: make fails, names the key, leaves no run.h5.
if ran bad > /dev/null; then fail "make bad succeeded"; fi
grep -q "no_such_key" "$tmp/log" || { cat "$tmp/log" >&2; fail "no message naming the key"; }
[ ! -e "$tmp/runs/bad/run.h5" ] || fail "runs/bad/run.h5 left behind"
ls "$tmp/runs/bad" | grep -q tmp && fail "temporary left in runs/bad"
rm -rf "$tmp"
echo "workflows: incremental re-runs, make -j2 and failures as expected"
