#!/bin/sh
# An interrupted calibration continues where it stopped: the runs done are
# taken from the log, none is repeated, and the result is the one an
# uninterrupted calibration gives, to the bit. The uninterrupted one is
# test_calibrate_recovery's (its output directory, WHOLE_DIR: the same
# calibration file and options, one run per core), so that calibration is
# not run twice; the interrupted one runs one run at a time, so the
# comparison also shows that the result does not depend on the scheduling.
# One killed outright (SIGKILL) takes its runs with it, and the next call
# gives the same result.
# Usage: resume.sh BIN_DIR DATA_DIR TMP_DIR WHOLE_DIR
set -eu
bin=$1 data=$2 tmp=$3 whole=$4
rm -rf "$tmp"
mkdir -p "$tmp"
fail() { echo "FAIL: $*" >&2; exit 1; }
opts="--quiet --no-png --no-sensitivity --jobs 1"
# shellcheck disable=SC2086
run() { "$bin/calibrate" $opts --out "$1" "$data/recovery.json"; }
field() { sed -n "s/.*\"$2\":[[:space:]]*\([0-9]*\).*/\1/p" "$1" | head -n 1; }
# logged_rows LOG N PID: wait until the calibration PID has logged N runs.
logged_rows() {
	i=0
	while [ "$(cat "$1" 2> /dev/null | wc -l)" -le "$2" ]; do
		sleep 0.1
		i=$((i + 1))
		[ $i -lt 1200 ] || { kill "$3"; fail "no $2 runs logged in $1 in 120 s"; }
	done
}

[ -s "$whole/report.json" ] ||
	fail "no uninterrupted calibration in $whole (test_calibrate_recovery makes it)"
runs=$(field "$whole/report.json" new)

# Stopped by SIGTERM once its log holds three runs.
# shellcheck disable=SC2086
"$bin/calibrate" $opts --out "$tmp/cut" "$data/recovery.json" > /dev/null 2> "$tmp/cut.err" &
pid=$!
logged_rows "$tmp/cut/log.csv" 3 $pid
kill -TERM $pid
status=0
wait $pid || status=$?
[ $status -eq 3 ] || { cat "$tmp/cut.err" >&2; fail "interrupted calibration: status $status, expected 3"; }
grep -q "interrupted: the runs done are kept in" "$tmp/cut.err" || fail "no message"
logged=$(($(wc -l < "$tmp/cut/log.csv") - 1))
[ ! -e "$tmp/cut/material.json" ] || fail "a material written by an interrupted calibration"

run "$tmp/cut" > /dev/null || fail "the continued calibration failed"
new=$(field "$tmp/cut/report.json" new)
from_log=$(field "$tmp/cut/report.json" from_log)
[ "$from_log" -eq "$logged" ] || fail "$from_log runs from the log, $logged were in it"
[ $((new + logged)) -eq "$runs" ] ||
	fail "$logged runs before the stop and $new after it; $runs without a stop"
cmp -s "$whole/material.json" "$tmp/cut/material.json" || fail "another material"
cmp -s "$whole/path.csv" "$tmp/cut/path.csv" || fail "another path"
# The logs hold the same runs in the same order: all but the run keys (a
# hash of the case and the assembly, which each directory packs anew) and
# the wall times.
cut -d, -f2- "$whole/log.csv" | sed 's/,[^,]*$//' > "$tmp/a"
cut -d, -f2- "$tmp/cut/log.csv" | sed 's/,[^,]*$//' > "$tmp/b"
cmp -s "$tmp/a" "$tmp/b" || { diff "$tmp/a" "$tmp/b" >&2; fail "the logs differ"; }

# Nothing left to run: a third call takes every run from the log, and its
# progress lines say so.
"$bin/calibrate" $(echo $opts | sed 's/--quiet//') --out "$tmp/cut" "$data/recovery.json" \
	> /dev/null 2> "$tmp/third.err" || fail "the third call failed"
[ "$(field "$tmp/cut/report.json" new)" -eq 0 ] || fail "the third call ran again"
grep -q "^calibrate: point 1, .* | runs [0-9]* of [0-9]*, from the log$" "$tmp/third.err" ||
	{ cat "$tmp/third.err" >&2; fail "the third call's points not shown as from the log"; }

# Killed outright (SIGKILL) with two runs going on: they die with it, so
# that none goes on writing the files of the runs the next call starts
# again, and the next call gives the same result, no run failed.
"$bin/calibrate" --quiet --no-png --no-sensitivity --jobs 2 --out "$tmp/killed" \
	"$data/recovery.json" > /dev/null 2>&1 &
pid=$!
logged_rows "$tmp/killed/log.csv" 2 $pid
kill -KILL $pid
wait $pid || true
sleep 0.5
! pgrep -f -- "$tmp/killed/" > /dev/null ||
	fail "runs of a killed calibration still going: $(pgrep -af -- "$tmp/killed/")"
run "$tmp/killed" > /dev/null || fail "the calibration continued after SIGKILL failed"
! grep -q ",failed" "$tmp/killed/log.csv" || fail "runs failed after SIGKILL: $(grep ,failed "$tmp/killed/log.csv")"
cmp -s "$whole/material.json" "$tmp/killed/material.json" || fail "another material after SIGKILL"
rm -rf "$tmp"
echo "calibrate: $logged runs before the stop, $new after it, $runs without a stop"
