#!/bin/sh
# Every signal that asks solve to end (Ctrl-C, a closed terminal, a batch
# scheduler's warning before its kill) finishes the step, checkpoints and
# leaves a complete run file that --restart continues; no temporary is left.
# Usage: signals.sh BIN_DIR TMP_DIR
set -eu
bin=$1 tmp=$2
rm -rf "$tmp"
mkdir -p "$tmp"
. "$(dirname "$0")/case.sh"
lattice 2000
case_file "$tmp/case.json" '"stop": {"steps": 100000000}'
for sig in INT TERM HUP USR1 USR2 XCPU; do
	out=$tmp/$sig.h5
	"$bin/solve" --quiet --threads 1 --output "$out" "$tmp/case.json" &
	pid=$!
	k=0
	while [ ! -e "$out.tmp" ] && [ $k -lt 300 ]; do sleep 0.05; k=$((k + 1)); done
	sleep 0.3
	kill -s "$sig" $pid
	code=0
	wait $pid || code=$?
	if [ $code -ne 3 ] || [ ! -f "$out" ] || [ -e "$out.tmp" ]; then
		echo "SIG$sig: exit $code (expected 3), run file $(ls "$out" 2>&1)" >&2
		exit 1
	fi
	code=0
	"$bin/solve" --quiet --restart "$out" --max-steps 5 || code=$?
	if [ $code -ne 3 ]; then
		echo "SIG$sig: the restart exited $code (expected 3, interrupted by its budget)" >&2
		exit 1
	fi
	echo "SIG$sig: interrupted, checkpointed and continued"
done
