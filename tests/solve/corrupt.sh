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

flip() { # FILE OFFSET: a copy at $tmp/c.h5 with that byte inverted
	cp "$1" "$tmp/c.h5"
	b=$(od -An -tu1 -j "$2" -N1 "$1" | tr -d ' ')
	printf "\\$(printf %o $((b ^ 255)))" |
		dd of="$tmp/c.h5" bs=1 seek="$2" conv=notrunc 2> /dev/null
}
bad=0
sweep() { # FILE WHAT COMMAND...: the command on each corrupted copy
	f=$1 what=$2
	shift 2
	n=$(wc -c < "$f")
	ok=0 refused=0 p=0
	while [ $p -lt $n ]; do
		flip "$f" $p
		code=0
		timeout 20 "$@" > /dev/null 2> "$tmp/err" || code=$?
		case $code in
		0 | 3) ok=$((ok + 1)) ;;
		1 | 2) refused=$((refused + 1)) ;;
		124) echo "$what: byte $p: no answer within 20 s" >&2; bad=1 ;;
		*) echo "$what: byte $p: exit $code: $(head -c 300 "$tmp/err")" >&2; bad=1 ;;
		esac
		if [ $p -lt 4096 ]; then p=$((p + step)); else p=$((p + n / 40 + 1)); fi
	done
	echo "$what: $((ok + refused)) corrupted copies: $ok read (or ran), $refused refused with a message"
}
sweep "$tmp/a.h5" "assembly" "$bin/solve" --quiet --max-steps 1 --assembly "$tmp/c.h5" \
	--output "$tmp/o.h5" "$tmp/case.json"
sweep "$tmp/run.h5" "run file" "$bin/post" vtk --out "$tmp/vtk" "$tmp/c.h5"
sweep "$tmp/int.h5" "checkpoint" "$bin/solve" --quiet --restart "$tmp/c.h5" --max-steps 1
exit $bad
