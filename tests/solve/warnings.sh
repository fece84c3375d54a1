#!/bin/sh
# Settings that would make a run hopelessly long are announced at setup with
# the estimate and the key that causes them; the run still starts. A
# snapshot strain a run never reached is named at its end.
# Usage: warnings.sh BIN_DIR TMP_DIR
set -eu
bin=$1 tmp=$2
rm -rf "$tmp"
mkdir -p "$tmp"
. "$(dirname "$0")/case.sh"
lattice 300
run() { # NAME RATE SKIN_KEY: solve one step, keep stderr
	case_file "$tmp/$1.json" "$3 \"stop\": {\"strain_axial\": 0.01}" "$2"
	code=0
	"$bin/solve" --max-steps 1 --output "$tmp/$1.h5" "$tmp/$1.json" 2> "$tmp/$1.err" || code=$?
	cat "$tmp/$1.err"
	[ $code -eq 3 ] || { echo "$1: exit $code, expected 3" >&2; exit 1; }
}
run slow 1e-9 ""
grep -q "warning: the loading program needs about [0-9.]*e+1[0-9] steps of .* (stage 1 the longest: check its until rule and axial.rate, or the stop rule)" "$tmp/slow.err"
run skin 1 '"neighbours": {"skin": 1e-12},'
grep -q "warning: neighbours.skin 1e-12 m: the ends move .* m per step, so the neighbour lists are rebuilt every few steps" "$tmp/skin.err"
run fine 1 ""
if grep "warning:" "$tmp/fine.err"; then
	echo "fine: a warning for settings that are fine" >&2
	exit 1
fi
# A snapshot strain the run never reaches (the list is taken in turn: 0.0001
# comes after 0.0003 only on the way back) is named at the end; not 0.0003,
# which the stop rule ends the run on (the last snapshot holds it).
case_file "$tmp/snap.json" '"output": {"snapshot_strains": [0.0002, 0.0003, 0.0001]}, "stop": {"strain_axial": 0.0003}' 20
"$bin/solve" --output "$tmp/snap.h5" "$tmp/snap.json" 2> "$tmp/snap.err"
grep -q "warning: output.snapshot_strains: 1 of 3 not reached (the first: 0.0001;" "$tmp/snap.err" || {
	cat "$tmp/snap.err"
	echo "snap: the strain never reached is not named" >&2
	exit 1
}
