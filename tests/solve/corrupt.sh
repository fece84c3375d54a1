#!/bin/sh
# One flipped byte in a file of this toolchain ends in a clear error or a
# correct result within seconds: never a hang, never a crash. Each kind of
# file is swept: the assembly (read by solve), a run file (read by post,
# snapshots and all) and an interrupted run's checkpoint (read by solve
# --restart); every byte of the first 4 kB in steps, where HDF5 keeps most
# of its metadata, and positions spread over the rest.
# Usage: corrupt.sh BIN_DIR TMP_DIR [STEP]
set -eu
bin=$1 tmp=$2 step=${3:-23}
rm -rf "$tmp"
mkdir -p "$tmp"
. "$(dirname "$0")/case.sh"
lattice 300
case_file "$tmp/case.json" '"output": {"history_every": 10, "snapshot_every": 100},
 "stop": {"steps": 200}' 1 2e6
"$bin/solve" --quiet --output "$tmp/run.h5" "$tmp/case.json"
code=0
"$bin/solve" --quiet --max-steps 150 --output "$tmp/int.h5" "$tmp/case.json" || code=$?
[ $code -eq 3 ]

# The offsets swept in FILE, each with its byte inverted (in octal): every
# STEP-th of the first 4 kB, then a fortieth of the file apart. One pass of
# od and awk over the file, so that each copy costs only cp and dd.
flips() {
	od -An -v -tu1 "$1" | awk -v step="$step" -v n="$(wc -c < "$1")" '
		BEGIN { for (p = 0; p < n; p += p < 4096 ? step : int(n / 40) + 1) at[p] = 1; k = 0 }
		{
			for (i = 1; i <= NF; i++) {
				if (k in at)
					printf "%d %o\n", k, 255 - $i
				k++
			}
		}'
}
bad=0
sweep() { # FILE WHAT COMMAND...: the command on each corrupted copy
	f=$1 what=$2
	shift 2
	ok=0 refused=0
	flips "$f" > "$tmp/flips"
	while read -r p inverted; do
		cp "$f" "$tmp/c.h5"
		printf "\\$inverted" | dd of="$tmp/c.h5" bs=1 seek="$p" conv=notrunc 2> /dev/null
		code=0
		timeout 20 "$@" < /dev/null > /dev/null 2> "$tmp/err" || code=$?
		case $code in
		0 | 3) ok=$((ok + 1)) ;;
		1 | 2) refused=$((refused + 1)) ;;
		124) echo "$what: byte $p: no answer within 20 s" >&2; bad=1 ;;
		*) echo "$what: byte $p: exit $code: $(head -c 300 "$tmp/err")" >&2; bad=1 ;;
		esac
	done < "$tmp/flips"
	echo "$what: $((ok + refused)) corrupted copies: $ok read (or ran), $refused refused with a message"
}
sweep "$tmp/a.h5" "assembly" "$bin/solve" --quiet --max-steps 1 --assembly "$tmp/c.h5" \
	--output "$tmp/o.h5" "$tmp/case.json"
sweep "$tmp/run.h5" "run file" "$bin/post" vtk --out "$tmp/vtk" "$tmp/c.h5"
sweep "$tmp/int.h5" "checkpoint" "$bin/solve" --quiet --restart "$tmp/c.h5" --max-steps 1
exit $bad
