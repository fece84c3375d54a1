#!/bin/sh
# A run whose stderr is a log, not a terminal, writes a progress line every
# --log-every seconds (step, share done, rate, elapsed time, ETA, stage,
# time, strain, stress, broken bonds), and none with --log-every 0. The
# broken bonds are those so far: in a run that breaks bonds, never fewer
# from one line to the next, and at the last line the run's cracks.
# Usage: log.sh BIN_DIR TMP_DIR
set -eu
bin=$1 tmp=$2
rm -rf "$tmp"
mkdir -p "$tmp"
. "$(dirname "$0")/case.sh"
lattice 300
case_file "$tmp/case.json" '"stop": {"steps": 6000}'
"$bin/solve" --log-every 0.05 --output "$tmp/run.h5" "$tmp/case.json" 2> "$tmp/log"
cat "$tmp/log"
lines=$(grep -c '^[0-9]*/6000 steps ([0-9]*%)  .* steps/s  .* elapsed, ETA .*  stage 1  t .* s  strain .*%  stress .* MPa  broken 0$' "$tmp/log")
[ "$lines" -ge 2 ] || { echo "expected progress lines in the log, found $lines" >&2; exit 1; }
"$bin/solve" --log-every 0 --output "$tmp/run.h5" "$tmp/case.json" 2> "$tmp/log"
! grep -q ' steps/s ' "$tmp/log"
case_file "$tmp/break.json" '"stop": {"steps": 6000}' 20 2e6
"$bin/solve" --log-every 0.01 --output "$tmp/break.h5" "$tmp/break.json" 2> "$tmp/log"
cracks=$(/usr/bin/python3 -c 'import sys, h5py; print(h5py.File(sys.argv[1], "r")["cracks/i"].shape[0])' "$tmp/break.h5")
sed -n 's/.* broken \([0-9]*\)$/\1/p' "$tmp/log" | awk -v cracks="$cracks" '
	$1 < last { print "broken bonds went down: " last " then " $1; bad = 1 }
	{ last = $1; n++ }
	END {
		if (n < 2) { print "expected progress lines, found " n; bad = 1 }
		if (last != cracks || cracks < 100) { print "last line: " last " broken, the run: " cracks " cracks"; bad = 1 }
		exit bad
	}' >&2
