#!/bin/sh
# Targets the law cannot reach together: a Brazilian strength twice what the
# truth's stresses give beside its UCS. With the strengths and E0 free, every
# key moves the two together, so the search stops on the best compromise
# (exit status 4) within its budget, says which targets conflict, and writes
# the material all the same. Its sensitivities move the keys tied to the
# free strength with it, as every run does.
# Usage: conflict.sh BIN_DIR DATA_DIR TMP_DIR
set -eu
bin=$1 data=$2 tmp=$3
rm -rf "$tmp"
mkdir -p "$tmp"
fail() { echo "FAIL: $*" >&2; exit 1; }
sed -e 's/"truth": "truth.json",//' \
	-e 's/{"test": "ucs", "quantity": "peak_stress"}/{"test": "ucs", "quantity": "peak_stress", "value": 15.5e6}/' \
	-e 's/{"test": "ucs", "quantity": "young_modulus"}/{"test": "ucs", "quantity": "young_modulus", "value": 19.5e9}/' \
	-e 's/{"test": "bts", "quantity": "bts_strength"}/{"test": "bts", "quantity": "bts_strength", "value": 3.0e6}/' \
	-e "s|\"truth.json\"|\"$data/truth.json\"|; s|\"ucs.json\"|\"$data/ucs.json\"|; s|\"bts.json\"|\"$data/bts.json\"|" \
	-e "s|\"cylinder.json\"|\"$data/cylinder.json\"|; s|\"disc.json\"|\"$data/disc.json\"|" \
	-e 's/"budget": {"runs": 20}/"budget": {"runs": 20}, "search": {"patience": 1}/' \
	"$data/recovery.json" > "$tmp/conflict.json"
status=0
"$bin/calibrate" --quiet --no-png --out "$tmp/out" "$tmp/conflict.json" > "$tmp/report.txt" ||
	status=$?
[ $status -eq 4 ] || { cat "$tmp/report.txt" >&2; fail "status $status, expected 4"; }
grep -q "conflict: ucs peak_stress (+[0-9.]* %) and bts bts_strength (-[0-9.]* %)" \
	"$tmp/report.txt" || { cat "$tmp/report.txt" >&2; fail "no conflict named"; }
grep -q "not met: bts bts_strength" "$tmp/report.txt" || fail "no target named as not met"
grep -q '"met":	false' "$tmp/out/report.json" || fail "report.json says met"
grep -q "targets not all met" "$tmp/out/material.json" || fail "material.json's name"
runs=$(sed -n 's/.*"search":[[:space:]]*\([0-9]*\).*/\1/p' "$tmp/out/report.json" | head -n 1)
[ "$runs" -lt 20 ] || fail "$runs search runs: the budget, not the diagnosis, ended it"
# Every run, those of the sensitivities too, keeps the tied stresses at
# their template ratio to the free one (the strength of the scaling).
/usr/bin/python3 -c '
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
phases = set(r["phase"] for r in rows)
ratios = set(round(float(r["shear_strength"]) / float(r["tensile_strength"]), 9) for r in rows)
if "sensitivity" not in phases or len(ratios) != 1:
    sys.exit("phases %s, shear/tensile strength ratios %s: expected one" % (sorted(phases), sorted(ratios)))' \
	"$tmp/out/log.csv" || fail "a run broke the tie of the stresses"
rm -rf "$tmp"
echo "calibrate: conflicting targets diagnosed after $runs search runs"
