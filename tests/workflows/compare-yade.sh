#!/bin/sh
# tools/compare-yade's plumbing and the mapping of the parameters onto Yade's:
# a cylinder of about 200 spheres cut from the thesis' packing
# (share/specimens/jcfpm-50x100-yade.txt), the JCFPM concrete UCS for 400
# steps with Yade's damping form in solve and solve's branch vectors in
# Yade (--yade-branch contact: for these equal spheres the same shear
# kinematics). Both programs must report the same number of bonds at start
# (the interaction range), the same strain (the end layers, their speed,
# the time step), and the same modulus and stress after the 400 steps to
# 1e-7: the same arithmetic (bond stiffnesses, masses, damping, loading and
# its start) up to rounding. They agree to about 1e-10; a start with the
# layers' speed in the first step's shear increments is 2e-4 off, Yade's
# default branch vectors 1.7 %. The tool must print every quantity and
# draw its PNG.
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
sh "$src/tools/compare-yade" --bin "$bin" --cut 0.014,0.028 --steps 400 --every 10 \
	--damping-form components --yade-branch contact \
	--out "$tmp/out" >"$tmp/lines.json"
cat "$tmp/lines.json"
python3 - "$tmp/lines.json" "$tmp/out" <<'PY'
import json, os, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
q = {l["quantity"]: l for l in lines}
fail = []
want = ["bonds", "past_peak", "peak_stress", "strain_at_peak", "modulus", "modulus_initial",
        "broken_at_peak", "broken_tension_at_peak", "broken_shear_at_peak",
        "strain_at_first_break", "broken_tension_at_end", "broken_shear_at_end",
        "stress_at_end", "strain_at_end"]
if sorted(q) != sorted(want):
    fail.append("quantities %s, expected %s" % (sorted(q), sorted(want)))
n = lines[0]["spheres"]
if not 150 <= n <= 300:
    fail.append("%d spheres, expected about 200" % n)
if lines[0]["end_step"] != 399:
    fail.append("last row at step %s, expected 399" % lines[0]["end_step"])
if not (q["bonds"]["solve"] == q["bonds"]["yade"] > n):
    fail.append("bonds: solve %s, yade %s" % (q["bonds"]["solve"], q["bonds"]["yade"]))
if abs(q["strain_at_end"]["rel_diff"]) > 1e-9:
    fail.append("strain at the end differs: %s" % q["strain_at_end"])
if not abs(q["modulus"]["rel_diff"]) <= 1e-7:
    fail.append("modulus: %s" % q["modulus"])
if not abs(q["stress_at_end"]["rel_diff"]) <= 1e-7:
    fail.append("stress after 400 steps: %s" % q["stress_at_end"])
if os.path.getsize(os.path.join(sys.argv[2], "compare.png")) < 10000:
    fail.append("compare.png missing or empty")
for f in fail:
    print("FAIL:", f)
sys.exit(1 if fail else 0)
PY
