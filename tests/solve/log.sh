#!/bin/sh
# A run whose stderr is a log, not a terminal, writes a progress line every
# --log-every seconds (step, share done, rate, elapsed time, ETA, stage,
# time, strain, stress, broken bonds), and none with --log-every 0.
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
