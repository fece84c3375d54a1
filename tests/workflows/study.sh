#!/bin/sh
# make study, end to end on share/studies/tiny.json (two points of a few
# hundred spheres, short runs): both points run side by side (-j2) and the
# table holds each point's summary.json; a second make runs nothing; a new
# value runs only its point, a changed material only solve and post; a
# point that fails (here pack: spheres too big for the cylinder) is
# reported, the other point still runs, make fails and the table marks it;
# a bad study file stops make with post's message before anything runs,
# and a missing one with make's.
# Usage: study.sh BIN_DIR SOURCE_DIR TMP_DIR   (KEEP=1 keeps TMP_DIR)
set -eu
bin=$1 src=$2 tmp=$3
rm -rf "$tmp"
mkdir -p "$tmp/share/studies" "$tmp/share/cases" "$tmp/share/materials"
cp "$src/share/cases/jcfpm-concrete-ucs.json" "$tmp/share/cases/"
cp "$src/share/materials/concrete-jcfpm.json" "$tmp/share/materials/"
cp "$src/share/studies/tiny.json" "$tmp/share/studies/t.json"
out=$tmp/runs/studies/t

fail() { echo "FAIL: $*" >&2; exit 1; }
# The programs a make run started, sorted, e.g. "pack pack post ... solve solve".
ran() {
	make -C "$src/workflows" BIN="$bin" SHARE="$tmp/share" OUT="$tmp/runs" THREADS=1 \
		study "$@" > "$tmp/log" 2>&1 || return 1
	grep -o "^$bin/[a-z]*" "$tmp/log" | sed "s|^$bin/||" | sort | tr '\n' ' ' | sed 's/ $//'
}
expect() { # expected-programs make-arguments...
	want=$1
	shift
	got=$(ran "$@") || { cat "$tmp/log" >&2; fail "make study $* failed"; }
	[ "$got" = "$want" ] || { cat "$tmp/log" >&2; fail "make study $*: ran '$got', expected '$want'"; }
}

# The plan, pack and solve of both points, their summaries and curves, the table.
expect "pack pack post post post post post post solve solve" STUDY=t -j2
for p in interaction_range-1.2 interaction_range-1.4; do
	for f in material.json case.json specimen.json assembly.h5 run.h5 summary.json curve.csv; do
		[ -s "$out/$p/$f" ] || fail "$p/$f missing"
	done
done
for f in runs.csv study.csv response.png curves.png; do
	[ -s "$out/$f" ] || fail "$f missing"
done
# Every row of runs.csv is its point's summary.json.
python3 - "$out" <<'PY' || fail "runs.csv differs from the points' summary.json"
import csv, json, math, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(out + "/runs.csv")))
assert [r["point"] for r in rows] == ["interaction_range-1.2", "interaction_range-1.4"], rows
for r in rows:
    s = json.load(open("%s/%s/summary.json" % (out, r["point"])))
    want = {"peak_stress_Pa": s["peak_stress"], "strain_at_peak": s["strain_at_peak"],
            "young_modulus_Pa": s["young_modulus"], "poisson_ratio": s["poisson_ratio"],
            "bonds": s["bonds"], "spheres": s["spheres"], "solid_fraction": s["solid_fraction"],
            "bonds_broken": s["bonds_broken_tension"] + s["bonds_broken_shear"],
            "wall_time_s": s["wall_time"]}
    for k, v in want.items():
        assert math.isclose(float(r[k]), v, rel_tol=1e-9), (r["point"], k, r[k], v)
    assert r["status"] == "ok" and r["seed"] == "1", r
    assert float(r["interaction_range"]) == float(r["point"].split("-")[1])
    print("%s: peak %.2f MPa at %.3f %%, %s spheres, solid fraction %.3f" % (
        r["point"], s["peak_stress"] / 1e6, 100 * s["strain_at_peak"], r["spheres"],
        s["solid_fraction"]))
study = list(csv.DictReader(open(out + "/study.csv")))
assert len(study) == 2 and study[1]["runs"] == "1" and study[1]["failed"] == "0", study
assert float(study[1]["peak_stress_Pa"]) == float(rows[1]["peak_stress_Pa"]), study
assert float(rows[1]["peak_stress_Pa"]) > float(rows[0]["peak_stress_Pa"])
PY

# Nothing changed: nothing runs.
expect "" STUDY=t
expect "" STUDY=t -n
# A new value: only its point runs (and the plan and the table).
sleep 1
sed -i 's/\[1.2, 1.4\]/[1.2, 1.3]/' "$tmp/share/studies/t.json"
expect "pack post post post post solve" STUDY=t
grep -q "^interaction_range-1.3," "$out/runs.csv" || fail "runs.csv: no point 1.3"
grep -q "^interaction_range-1.4," "$out/runs.csv" && fail "runs.csv: point 1.4 left in"
# A changed material: solve and post of both points, not pack.
sleep 1
sed -i 's/"cohesion": 9e6/"cohesion": 9.5e6/' "$tmp/share/materials/concrete-jcfpm.json"
expect "post post post post post post solve solve" STUDY=t -j2

# A failing point: reported, the other completes, the table marks it.
sed 's/"material.interaction_range", "values": \[1.2, 1.4\]/"specimen.radius", "values": [0.0015, 0.009]/' \
	"$src/share/studies/tiny.json" > "$tmp/share/studies/tfail.json"
if ran STUDY=tfail > /dev/null; then fail "make study with a failing point succeeded"; fi
grep -q "do not fit in the specimen" "$tmp/log" || { cat "$tmp/log" >&2; fail "pack's message missing"; }
grep -q "some points failed" "$tmp/log" || { cat "$tmp/log" >&2; fail "no failure reported"; }
fout=$tmp/runs/studies/tfail
[ -s "$fout/radius-0.0015/summary.json" ] || fail "the good point did not run"
grep -q "^radius-0.009,0.009,1,failed,pack," "$fout/runs.csv" || { cat "$fout/runs.csv" >&2; fail "runs.csv does not mark the failed point"; }
grep -q "^0.009,1,1," "$fout/study.csv" || { cat "$fout/study.csv" >&2; fail "study.csv does not count the failure"; }

# A bad study file: post's message, nothing run, nothing lost.
sed 's/"values": \[1.2, 1.4\]/"values": [1.2, 2.5]/' "$src/share/studies/tiny.json" \
	> "$tmp/share/studies/t.json"
if ran STUDY=t > /dev/null; then fail "make study with a bad value succeeded"; fi
grep -q "t.json: point interaction_range-2.5: case: key 'material.interaction_range': value 2.5: expected a number in \[1, 2\]" "$tmp/log" ||
	{ cat "$tmp/log" >&2; fail "no message naming the value"; }
[ -s "$out/interaction_range-1.3/run.h5" ] || fail "a computed point was lost"
if ran STUDY=nope > /dev/null; then fail "make study with no study file succeeded"; fi
grep -q "STUDY=nope: no study file .*/share/studies/nope.json: expected one of t tfail" "$tmp/log" ||
	{ cat "$tmp/log" >&2; fail "no message naming the missing study file"; }
[ -n "${KEEP:-}" ] || rm -rf "$tmp"
echo "study: points side by side, the table, incremental re-runs, failures as expected"
