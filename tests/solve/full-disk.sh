#!/bin/sh
# A full disk (here a file-size limit, which fails writes the same way):
# solve and pack stop with one message naming the file and a non-zero exit,
# not a crash inside HDF5; the output they would have replaced is kept, no
# temporary is left, and solve notices at its next flush, not at the end of
# a run that would never end.
# Usage: full-disk.sh BIN_DIR TMP_DIR
set -eu
bin=$1 tmp=$2
rm -rf "$tmp"
mkdir -p "$tmp"
. "$(dirname "$0")/case.sh"
lattice 3000
case_file "$tmp/case.json" '"output": {"snapshot_every": 200}, "stop": {"steps": 1000000000}'
limited() { # BLOCKS COMMAND...: the command, with writes beyond BLOCKS of 512 bytes failing
	(ulimit -f "$1"; shift; trap '' XFSZ; exec "$@")
}
check() { # NAME FILE CODE: exit 1, one message naming the file, the old file kept
	if [ "$3" -ne 1 ] || ! grep -q "^$1: $2.tmp: cannot write .*: \(File too large\|the file system is full\)" "$tmp/err"; then
		echo "$1: exit $3, said:" >&2
		cat "$tmp/err" >&2
		exit 1
	fi
	[ ! -e "$2.tmp" ] || { echo "$1: $2.tmp left behind" >&2; exit 1; }
	cksum < "$2" | cmp -s - "$tmp/before" || { echo "$1: $2 changed" >&2; exit 1; }
	cat "$tmp/err"
}

"$bin/solve" --quiet --max-steps 10 --output "$tmp/run.h5" "$tmp/case.json" || [ $? -eq 3 ]
cksum < "$tmp/run.h5" > "$tmp/before"
code=0
limited 2048 "$bin/solve" --quiet --output "$tmp/run.h5" "$tmp/case.json" 2> "$tmp/err" || code=$?
check solve "$tmp/run.h5" $code

cp "$tmp/a.h5" "$tmp/p.h5"
cksum < "$tmp/p.h5" > "$tmp/before"
code=0
limited 256 "$bin/pack" --quiet --count 10000 --shape box "$tmp/p.h5" 2> "$tmp/err" || code=$?
check pack "$tmp/p.h5" $code
