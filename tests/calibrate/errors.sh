#!/bin/sh
# Bad calibration files (and the cases they name) and a start that fails:
# exit status 1 and one message naming the file, the key, the value and what
# was expected; nothing is run (no output directory) when the files are at
# fault.
# Usage: errors.sh BIN_DIR DATA_DIR TMP_DIR
set -eu
bin=$1 data=$2 tmp=$3
rm -rf "$tmp"
mkdir -p "$tmp"
cp "$data"/*.json "$tmp"/

fail() { echo "FAIL: $*" >&2; exit 1; }

# write FREE TESTS TARGETS [EXTRA]: a calibration file cal.json
write() {
	cat > "$tmp/cal.json" <<JSON
{"material": "truth.json",
 "free": [$1],
 "tests": [$2],
 "targets": [$3]${4:+, $4}}
JSON
}
free='{"key": "nu", "min": 0.1, "max": 0.4}'
tests='{"name": "ucs", "case": "ucs.json", "search": {"specimen": "cylinder.json"}}'
target='{"test": "ucs", "quantity": "poisson_ratio", "value": 0.2}'

# expect STATUS MESSAGE: run calibrate on cal.json
expect() {
	rm -rf "$tmp/out"
	set +e
	"$bin/calibrate" --quiet --no-png --out "$tmp/out" "$tmp/cal.json" > "$tmp/stdout" \
		2> "$tmp/stderr"
	status=$?
	set -e
	[ "$status" -eq "$1" ] || { cat "$tmp/stderr" >&2; fail "status $status, expected $1: $2"; }
	grep -qF -- "$2" "$tmp/stderr" || { cat "$tmp/stderr" >&2; fail "no message '$2'"; }
	[ "$(wc -l < "$tmp/stderr")" -eq 1 ] || { cat "$tmp/stderr" >&2; fail "more than one line"; }
}
expect_nothing_run() {
	expect 1 "$1"
	[ ! -e "$tmp/out" ] || fail "an output directory for a bad file: $1"
}

write "$free" "$tests" "$target"
sed -i 's/"truth.json"/"none.json"/' "$tmp/cal.json"
expect_nothing_run "cal.json: key 'material': value \"none.json\": no readable file $tmp/none.json: expected a material file (its name relative to the calibration file's directory) or a material object"
write "$free" "$tests" "$target" '"budgett": {"runs": 3}'
expect_nothing_run "cal.json: key 'budgett': unknown key"
write "$free" "$tests" '{"test": "ucs", "quantity": "peak_strength", "value": 1e6}'
expect_nothing_run "cal.json: key 'targets[0].quantity': value \"peak_strength\": expected one of peak_stress, peak_deviator,"
write '{"key": "nu", "min": 0.25, "max": 0.45}' "$tests" "$target"
expect_nothing_run "cal.json: key 'free[0].min': the bounds [0.25, 0.45] exclude the start, the template's nu = 0.2"
write '{"key": "nu", "min": 0.1, "max": 0.4, "start": 0.45}' "$tests" "$target"
expect_nothing_run "cal.json: key 'free[0].start': value 0.45: the bounds [0.1, 0.4] exclude it"
write '{"key": "E", "min": 1e9, "max": 1e11}' "$tests" "$target"
expect_nothing_run "cal.json: key 'free[0].key': value \"E\": not a number of the material template (law onate): expected one of density, E0, nu,"
write '{"key": "nu", "min": 0.4, "max": 0.1}' "$tests" "$target"
expect_nothing_run "cal.json: key 'free[0].max': value 0.1: expected a number greater than min = 0.4"
write '{"key": "nu", "min": 0, "max": 0.4, "log": true}' "$tests" "$target"
expect_nothing_run "cal.json: key 'free[0].min': value 0: expected a positive number (log scale)"
write '{"key": "nu", "min": 0.1, "max": 0.6}' "$tests" "$target"
expect_nothing_run "cal.json: key 'free[0].max': value 0.6: the material: key 'nu': value 0.6: expected a number in [0, 0.5]"
write "$free" "$tests" '{"test": "uniaxial", "quantity": "peak_stress", "value": 1e6}'
expect_nothing_run "cal.json: key 'targets[0].test': value \"uniaxial\": no such test: expected one of 'ucs'"
write "$free" "$tests" '{"test": "ucs", "quantity": "bts_strength", "value": 1e6}'
expect_nothing_run "cal.json: key 'targets[0].quantity': value \"bts_strength\": not measured by a \"ucs\" test"
write "$free" "$tests" '{"test": "ucs", "quantity": "peak_stress", "value": -1e6}'
expect_nothing_run "cal.json: key 'targets[0].value': value -1000000: expected a positive number (Pa)"
# Targets in MPa, GPa or percent, not in SI.
write "$free" "$tests" '{"test": "ucs", "quantity": "peak_stress", "value": 10}'
expect_nothing_run "cal.json: key 'targets[0].value': value 10 (test 'ucs', peak_stress): 10 Pa is too small for a stress of a rock, a concrete or a cement: expected Pa, at least 1e3 (1 kPa); did you mean 10e6 (10 MPa)?"
write "$free" "$tests" "$target"', {"test": "ucs", "quantity": "young_modulus", "value": 4000}'
expect_nothing_run "cal.json: key 'targets[1].value': value 4000 (test 'ucs', young_modulus): 4000 Pa is too small for a modulus of a rock, a concrete or a cement: expected Pa, at least 1e6 (1 MPa); did you mean 4000e6 (4000 MPa)?"
write "$free" "$tests" '{"test": "ucs", "quantity": "young_modulus", "value": 28}'
expect_nothing_run "did you mean 28e9 (28 GPa)?"
write "$free" "$tests" '{"test": "ucs", "quantity": "strain_at_peak", "value": 5}'
expect_nothing_run "cal.json: key 'targets[0].value': value 5 (test 'ucs', strain_at_peak): a strain above 1 (100 %): expected a fraction, not a percent; did you mean 0.05 (5 %)?"
write "$free" '{"name": "ucs", "case": "ucs.json", "search": {"specimen": "none.json"}}' "$target"
expect_nothing_run "cal.json: key 'tests[0].search.specimen': value \"none.json\": no readable file"
write "$free" "$tests" "$target" '"search": {"method": "newton"}'
expect_nothing_run "cal.json: key 'search.method': value \"newton\": expected one of 'bobyqa', 'cobyla', 'sbplx'"
sed 's/"law": "onate"/"law": "exponential"/' "$data/truth.json" > /dev/null
printf '%s\n' '{"name": "e", "law": "exponential", "density": 2500, "E0": 28e9, "nu": 0.2,' \
	'"tensile_strength": 5e6, "delta_n": 0.2, "cohesion": 8e6, "friction_angle_deg": 30,' \
	'"contact_friction_angle_deg": 30, "interaction_range": 1.2}' > "$tmp/exponential.json"
write '{"key": "E0", "min": 1e9, "max": 1e11}' "$tests" "$target" '"search": {"scaling": true}'
sed -i 's/"truth.json"/"exponential.json"/' "$tmp/cal.json"
expect_nothing_run "cal.json: key 'search.scaling': value true: the law 'exponential' has no exact scaling"

# A budget too small for the global stage: a warning at the start, before
# anything is run (here --bin stops it there), with the numbers.
write "$free" "$tests" "$target" '"budget": {"runs": 10}, "search": {"global": "always"}'
set +e
"$bin/calibrate" --quiet --no-png --bin "$tmp/nowhere" --out "$tmp/out" "$tmp/cal.json" \
	> /dev/null 2> "$tmp/stderr"
set -e
grep -qF "calibrate: warning: $tmp/cal.json: the budget of 10 runs cannot finish the global stage: the start and the global stage's 16 points (search.global_points, by default 8 x (n + 1) = 16 for n = 1 search variable) take up to 17 runs" "$tmp/stderr" ||
	{ cat "$tmp/stderr" >&2; fail "no warning of a budget too small for the global stage"; }
grep -qF "give budget.runs (or --runs) of at least 18" "$tmp/stderr" || fail "no least budget"
write "$free" "$tests" "$target" '"budget": {"runs": 18}, "search": {"global": "always"}'
set +e
"$bin/calibrate" --quiet --no-png --bin "$tmp/nowhere" --out "$tmp/out" "$tmp/cal.json" \
	> /dev/null 2> "$tmp/stderr"
set -e
! grep -q "warning" "$tmp/stderr" || { cat "$tmp/stderr" >&2; fail "a warning for a budget that suffices"; }

# A case that solve refuses: found before anything is packed or run, and
# named with the calibration file and the test.
sed 's/"test": "ucs"/"no_such_key": 1, "test": "ucs"/' "$data/ucs.json" > "$tmp/ucs.json"
write "$free" "$tests" "$target"
expect_nothing_run "cal.json: test 'ucs': case $tmp/ucs.json: key 'no_such_key': unknown key"
cp "$data/ucs.json" "$tmp/ucs.json"

# A start that fails (an assembly solve cannot read): solve's message.
echo "not an assembly" > "$tmp/bogus.h5"
write "$free" '{"name": "ucs", "case": "ucs.json", "search": {"assembly": "bogus.h5"}}' "$target"
expect 1 "cal.json: the start fails: test 'ucs' (run $tmp/out/runs/"
grep -q "bogus.h5: not a readable HDF5 file" "$tmp/stderr" || fail "the message does not quote solve's"
rm -rf "$tmp"
echo "calibrate: bad calibration files and a failing case refused as expected"
