#!/bin/sh
# tools/compare-yade's plumbing and the mapping of the parameters onto Yade's:
# the JCFPM concrete UCS on a cylinder of about 200 spheres and the
# Brazilian test on a disc of about 120, cut from the thesis' packing
# (share/specimens/jcfpm-50x100-yade.txt), for 400 steps, like for like
# (Yade's damping form and contact conventions in solve, solve's branch
# vectors in Yade: for these equal spheres the same kinematics). Both
# programs must report the same number of bonds at start (the interaction
# range), the same strain (the end layers or platens, their speed, the time
# step), and the same modulus and stress after the 400 steps to 1e-7: the
# same arithmetic up to rounding (bond stiffnesses, masses, damping,
# loading and its start, platen contacts). They agree to about 1e-10; a
# start with the layers' speed in the first step's shear increments is
# 2e-4 off, solve's own platen contacts 3e-6, Yade's default branch
# vectors 1.7 %. The tool must print every quantity and draw its PNGs.
# With --samples 2 it must run two pairs (the second with Yade's list
# reordered and the time step 1e-12 longer) and print each quantity over
# them.
# Skipped (exit status 77) without yade; with DEM_REQUIRE_YADE=1 that is a
# failure instead.
# Usage: compare-yade.sh BIN_DIR SOURCE_DIR SCRATCH_DIR
set -eu
bin=$1 src=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp"
if ! command -v yade >/dev/null; then
	if [ "${DEM_REQUIRE_YADE:-0}" = 1 ]; then
		echo "FAIL: yade is not installed (DEM_REQUIRE_YADE=1)"
		exit 1
	fi
	echo "SKIPPED: yade is not installed (Debian package yade)"
	exit 77
fi
# The UCS (end layers) on about 200 spheres, and the Brazilian test
# (platens) on a disc of about 120.
sh "$src/tools/compare-yade" --bin "$bin" --cut 0.014,0.028 --steps 400 --every 10 \
	--damping-form components --yade-branch contact \
	--out "$tmp/ucs" >"$tmp/ucs.json"
sh "$src/tools/compare-yade" --bin "$bin" --cut 0.02,0.01 --steps 400 --every 10 \
	--case "$src/share/cases/jcfpm-concrete-bts.json" \
	--damping-form components --yade-branch contact \
	--out "$tmp/bts" >"$tmp/bts.json"
sh "$src/tools/compare-yade" --bin "$bin" --cut 0.014,0.028 --steps 200 --every 10 \
	--damping-form components --yade-branch contact --samples 2 \
	--out "$tmp/samples" >"$tmp/samples.json"
cat "$tmp/ucs.json" "$tmp/bts.json" "$tmp/samples.json"
python3 - "$tmp" <<'PY'
import json, os, sys
fail = []
for test, lo, hi in (("ucs", 150, 300), ("bts", 80, 200)):
    lines = [json.loads(l) for l in open(os.path.join(sys.argv[1], test + ".json"))]
    q = {l["quantity"]: l for l in lines}
    want = ["bonds", "past_peak", "peak_stress", "strain_at_peak", "modulus",
            "modulus_yade_window", "modulus_initial", "broken_at_peak", "broken_tension_at_peak",
            "broken_shear_at_peak", "strain_at_first_break", "broken_tension_at_end",
            "broken_shear_at_end", "stress_at_end", "strain_at_end"]
    if sorted(q) != sorted(want):
        fail.append("%s: quantities %s, expected %s" % (test, sorted(q), sorted(want)))
        continue
    n = lines[0]["spheres"]
    if not lo <= n <= hi:
        fail.append("%s: %d spheres, expected %d to %d" % (test, n, lo, hi))
    if lines[0]["end_step"] != 399:
        fail.append("%s: last row at step %s, expected 399" % (test, lines[0]["end_step"]))
    if not (q["bonds"]["solve"] == q["bonds"]["yade"] > n):
        fail.append("%s: bonds: solve %s, yade %s" % (test, q["bonds"]["solve"],
                                                      q["bonds"]["yade"]))
    if abs(q["strain_at_end"]["rel_diff"]) > 1e-9:
        fail.append("%s: strain at the end differs: %s" % (test, q["strain_at_end"]))
    if not abs(q["modulus"]["rel_diff"]) <= 1e-7:
        fail.append("%s: modulus: %s" % (test, q["modulus"]))
    if not abs(q["stress_at_end"]["rel_diff"]) <= 1e-7:
        fail.append("%s: stress after 400 steps: %s" % (test, q["stress_at_end"]))
    if os.path.getsize(os.path.join(sys.argv[1], test, "compare.png")) < 10000:
        fail.append("%s: compare.png missing or empty" % test)
lines = [json.loads(l) for l in open(os.path.join(sys.argv[1], "samples.json"))]
q = {l["quantity"]: l for l in lines}
if "peak_stress" not in q or "modulus_yade_window" not in q:
    fail.append("samples: quantities %s" % sorted(q))
else:
    dt = [json.load(open(os.path.join(sys.argv[1], "samples", "sample-%d" % k, "yade.json")))["dt"]
          for k in (0, 1)]
    if not (q["stress_at_end"]["samples"] == 2 and len(q["stress_at_end"]["solve"]) == 2
            and 0.5e-12 < dt[1] / dt[0] - 1 < 1.5e-12):
        fail.append("samples: %s, time steps %s" % (q["stress_at_end"], dt))
    a, b = q["stress_at_end"]["solve_mean"], q["stress_at_end"]["yade_mean"]
    if not abs(q["stress_at_end"]["rel_diff"] - (a - b) / b) < 1e-15 or \
            not abs(q["stress_at_end"]["rel_diff"]) < 1e-7:
        fail.append("samples: stress at the end %s" % q["stress_at_end"])
for f in fail:
    print("FAIL:", f)
sys.exit(1 if fail else 0)
PY
