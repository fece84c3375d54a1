#!/bin/sh
# The ParaView script renders a run headless, as the README runs it, and the
# picture shows the run: post_synth -> post vtk, post curve -> pvbatch
# share/paraview/show_run.py (default size) -> paraview_check.py (size, not
# blank, each crack disc in the colour of the strain at which it formed and
# each sphere behind the cut in the colour of its damage, where they are),
# then again with --bonds (each broken bond in the colour of its mode too)
# and at 640 x 480 (each view's title within it at every size);
# then tools/render-series --every 4: one numbered picture per frame kept
# (of the run's five, the first and the last: each is a pvbatch start of
# seconds), the first and the last different; with ffmpeg, the video of
# them.
# Skipped (exit status 77) with the reason when pvbatch cannot run here;
# with DEM_REQUIRE_PARAVIEW=1 (tools/check, which installs ParaView) that is
# a failure instead.
# Usage: paraview.sh BIN_DIR SOURCE_DIR SCRATCH_DIR
set -eu
bin=$1 src=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp"
skip() {
	if [ "${DEM_REQUIRE_PARAVIEW:-0}" = 1 ]; then
		echo "FAIL: $* (DEM_REQUIRE_PARAVIEW=1)"
		exit 1
	fi
	echo "SKIPPED: $*"
	exit 77
}
marker="tools/deps --optional installs this"
pv=$(command -v pvbatch) || pv=""
# The pvbatch of tools/deps, even where /usr/local/bin is not first on PATH.
if { [ -z "$pv" ] || ! grep -q "$marker" "$pv"; } && grep -qs "$marker" /usr/local/bin/pvbatch; then
	echo "note: using /usr/local/bin/pvbatch, not ${pv:-none} (PATH=$PATH)"
	pv=/usr/local/bin/pvbatch
fi
[ -n "$pv" ] || skip "pvbatch not found (tools/deps --optional installs it)"
# The pvbatch tools/deps installs starts its own virtual display when there
# is none; Debian's own needs one.
xvfb=no
if [ -z "${DISPLAY:-}" ] && ! grep -q "$marker" "$pv"; then
	command -v xvfb-run >/dev/null 2>&1 ||
		skip "no X display and no xvfb-run for pvbatch (Debian: xvfb xauth)"
	xvfb=yes
fi
run_pvbatch() {
	if [ $xvfb = yes ]; then
		xvfb-run -a -s "-screen 0 1920x1200x24 -noreset" "$pv" "$@"
	else
		"$pv" "$@"
	fi
}
echo 'import paraview.simple' >"$tmp/probe.py"
if ! run_pvbatch "$tmp/probe.py" >"$tmp/probe.log" 2>&1; then
	tail -n 5 "$tmp/probe.log"
	skip "$pv cannot import paraview.simple (python3-paraview conflicts with libvtk9-dev;" \
		"tools/deps --optional sets up pvbatch beside it)"
fi
/usr/bin/python3 -c 'import vtkmodules.vtkIOImage' 2>/dev/null ||
	skip "Debian's python3 has no vtkmodules to read the picture (python3-vtk9)"

"$bin/post_synth" --particles 300 "$tmp/run.h5"
"$bin/post" vtk "$tmp/run.h5" >/dev/null
"$bin/post" curve --no-png "$tmp/run.h5" >/dev/null
(cd "$src" && run_pvbatch share/paraview/show_run.py "$tmp/vtk" "$tmp/show.png")
/usr/bin/python3 "$src/tests/post/paraview_check.py" "$tmp/show.png" "$tmp/vtk" 1280 640
(cd "$src" && run_pvbatch share/paraview/show_run.py "$tmp/vtk" "$tmp/bonds.png" --bonds)
/usr/bin/python3 "$src/tests/post/paraview_check.py" "$tmp/bonds.png" "$tmp/vtk" 1920 640 --bonds
# A narrower picture: the text shrinks with the views.
(cd "$src" && run_pvbatch share/paraview/show_run.py "$tmp/vtk" "$tmp/small.png" --size 640 480)
/usr/bin/python3 "$src/tests/post/paraview_check.py" "$tmp/small.png" "$tmp/vtk" 640 480

# The series: every fourth frame and the last, numbered from 0.
every=4
nt=$(grep -c 'timestep=' "$tmp/vtk/particles.pvd")
want=$(((nt - 1) / every + 1))
[ $(((nt - 1) % every)) -eq 0 ] || want=$((want + 1))
if [ $xvfb = yes ]; then
	xvfb-run -a -s "-screen 0 1920x1200x24 -noreset" sh "$src/tools/render-series" \
		"$tmp/vtk" "$tmp/frames" --every $every
else
	PATH=$(dirname "$pv"):$PATH sh "$src/tools/render-series" "$tmp/vtk" "$tmp/frames" --every $every
fi
got=$(ls "$tmp/frames" | grep -c '^frame_[0-9][0-9][0-9][0-9]\.png$')
last=$(printf 'frame_%04d.png' $((want - 1)))
echo "series: $nt frames in the run, $got pictures, $want expected"
[ "$got" -eq "$want" ] && [ -s "$tmp/frames/$last" ] ||
	{ echo "FAIL: render-series wrote $got pictures, expected $want"; exit 1; }
! cmp -s "$tmp/frames/frame_0000.png" "$tmp/frames/$last" ||
	{ echo "FAIL: the first and last pictures of the series are the same"; exit 1; }
# With ffmpeg (tools/deps --optional installs it), the video: H.264, one
# video frame per picture.
if command -v ffprobe > /dev/null; then
	frames=$(ffprobe -v error -select_streams v:0 -show_entries stream=codec_name,nb_frames \
		-of csv=p=0 "$tmp/frames/fracture.mp4")
	echo "video: $frames"
	[ "$frames" = "h264,$want" ] ||
		{ echo "FAIL: fracture.mp4 is '$frames', expected h264 with $want frames"; exit 1; }
fi
