#!/bin/sh
# The workflows re-run exactly what changed: nothing when nothing changed;
# solve and post, not pack, when a material file changes; everything when the
# specimen or the seed changes. Two cases run side by side with make -j2, and
# a failing solve leaves no run.h5 that make would take as complete.
# A run may take another case's file and a sphere count of its own.
# Usage: make.sh BIN_DIR SOURCE_DIR TMP_DIR
set -eu
bin=$1 src=$2 tmp=$3
rm -rf "$tmp"
mkdir -p "$tmp/share/specimens" "$tmp/share/cases" "$tmp/share/materials"
cat > "$tmp/share/specimens/small.json" <<'JSON'
{"shape": "cylinder", "diameter": 0.012, "height": 0.024, "rmin": 0.0006, "rmax": 0.0012}
JSON
cat > "$tmp/share/materials/m.json" <<'JSON'
{"name": "m", "law": "linear", "density": 1700, "E": 10e9, "nu": 0.2,
 "tensile_strength": 5e6, "shear_strength": 10e6, "mu2": 0.5, "contact": {"friction": 0.5}}
JSON
for c in a b; do
	cat > "$tmp/share/cases/$c.json" <<'JSON'
{"test": "ucs", "assembly": "assembly.h5", "material": "../materials/m.json",
 "damping": {"translational": 0.1, "rotational": 0.1},
 "loading": [{"name": "axial", "axial": {"mode": "strain_rate", "rate": 5.0}}],
 "stop": {"strain_axial": 0.001}}
JSON
done
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

expect "pack solve post post post post" a
for f in assembly.h5 assembly.d pack.txt run.h5 run.d report.json summary.json curve.csv \
	stress_strain.png cracks.csv vtk/run.pvd; do
	[ -s "$tmp/runs/a/$f" ] || fail "runs/a/$f missing"
done
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
expect "pack solve post post post post" a

# Side by side: both complete, each with its own files.
ran -j2 a b > /dev/null || { cat "$tmp/log" >&2; fail "make -j2 a b failed"; }
[ -s "$tmp/runs/b/vtk/run.pvd" ] || fail "make -j2: runs/b incomplete"

# A run of another run's case with a sphere count of its own.
expect "pack solve post post post post" c COUNT=900
grep -q -- "--count 300 " "$tmp/runs/c/pack.args" || fail "c.count not used"
grep -q "cases/a.json" "$tmp/runs/c/run.d" || fail "c.case not used"

# A case solve rejects: make fails, names the key, leaves no run.h5.
if ran bad > /dev/null; then fail "make bad succeeded"; fi
grep -q "no_such_key" "$tmp/log" || { cat "$tmp/log" >&2; fail "no message naming the key"; }
[ ! -e "$tmp/runs/bad/run.h5" ] || fail "runs/bad/run.h5 left behind"
ls "$tmp/runs/bad" | grep -q tmp && fail "temporary left in runs/bad"
rm -rf "$tmp"
echo "workflows: incremental re-runs, make -j2 and failures as expected"
