#!/bin/sh
# The ParaView script renders a run headless: post_synth -> post vtk ->
# pvbatch share/paraview/show_run.py -> a PNG of some substance.
# Skipped (exit status 77) with the reason when pvbatch cannot run here.
# Usage: paraview.sh BIN_DIR SOURCE_DIR SCRATCH_DIR
set -eu
bin=$1 src=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp"
if ! command -v pvbatch >/dev/null 2>&1; then
	echo "SKIPPED: pvbatch not found (Debian: paraview and python3-paraview; see share/doc/post.md)"
	exit 77
fi
x=""
if [ -z "${DISPLAY:-}" ]; then
	if ! command -v xvfb-run >/dev/null 2>&1; then
		echo "SKIPPED: no X display and no xvfb-run for pvbatch (Debian: xvfb xauth)"
		exit 77
	fi
	x="xvfb-run -a"
fi
echo 'import paraview.simple' >"$tmp/probe.py"
if ! $x pvbatch "$tmp/probe.py" >/dev/null 2>&1; then
	echo "SKIPPED: pvbatch cannot import paraview.simple (Debian: python3-paraview, which" \
		"conflicts with libvtk9-dev; see share/doc/post.md for PYTHONPATH)"
	exit 77
fi
"$bin/post_synth" --particles 300 "$tmp/run.h5"
"$bin/post" vtk "$tmp/run.h5" >/dev/null
$x pvbatch "$src/share/paraview/show_run.py" "$tmp/vtk" "$tmp/show.png" --size 1200 600
sig=$(head -c 8 "$tmp/show.png" | od -An -tx1 | tr -d ' \n')
size=$(wc -c <"$tmp/show.png")
echo "show.png: signature $sig, $size bytes"
test "$sig" = "89504e470d0a1a0a"
test "$size" -gt 40000
