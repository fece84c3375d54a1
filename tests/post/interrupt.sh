#!/bin/sh
# post vtk interrupted (Ctrl-C: SIGINT) while it writes its frames: it dies
# of the signal, removes its staging directory with the frames written so
# far (vtk/.vtk.new), and leaves the series written before it as it was.
# Usage: interrupt.sh BIN_DIR SCRATCH_DIR
set -eu
bin=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$bin/post_synth" --particles 300 --snapshots 3 "$tmp/small.h5" > /dev/null
"$bin/post_synth" --particles 20000 --radius 0.0002 --snapshots 40 "$tmp/big.h5" > /dev/null
"$bin/post" vtk --out "$tmp/vtk" "$tmp/small.h5" > /dev/null
(cd "$tmp/vtk" && ls -A | sort && cat ./*) > "$tmp/before"

"$bin/post" vtk --threads 1 --out "$tmp/vtk" "$tmp/big.h5" > "$tmp/log" 2>&1 &
pid=$!
i=0
until [ -n "$(ls -A "$tmp/vtk/.vtk.new" 2> /dev/null)" ]; do
	i=$((i + 1))
	[ $i -lt 600 ] || fail "no staged frame after 30 s"
	sleep 0.05
done
kill -INT $pid
status=0
wait $pid || status=$?
[ $status -eq 130 ] || { cat "$tmp/log" >&2; fail "post vtk: status $status, expected 130 (SIGINT)"; }
[ ! -e "$tmp/vtk/.vtk.new" ] || fail "the staging directory is left: $(ls -A "$tmp/vtk/.vtk.new" | head -3)"
(cd "$tmp/vtk" && ls -A | sort && cat ./*) > "$tmp/after"
cmp -s "$tmp/before" "$tmp/after" || fail "the earlier series changed"
echo "post vtk interrupted: staging directory removed, earlier series kept"
