#!/bin/sh
# The run file opens in the Python ecosystem (h5py, xarray through
# h5netcdf) as share/doc/format.md says: python.py checks a small run with
# cracks and snapshots.
# Usage: python.sh BIN_DIR TMP_DIR
set -eu
bin=$1 tmp=$2
rm -rf "$tmp"
mkdir -p "$tmp"
. "$(dirname "$0")/case.sh"
lattice 200
case_file "$tmp/case.json" '"stop": {"steps": 1500},
 "output": {"history_every": 100, "snapshot_every": 500}' 20 2e6
"$bin/solve" --quiet --output "$tmp/run.h5" "$tmp/case.json"
/usr/bin/python3 "$(dirname "$0")/python.py" "$tmp/run.h5"
# The same run made by a build of format 2 and interrupted at step 700
# (data/format2-interrupted.h5) continues to the end with this build.
cp "$(dirname "$0")/data/format2-interrupted.h5" "$tmp/old.h5"
"$bin/solve" --quiet --restart "$tmp/old.h5"
"$bin/post" summary --out "$tmp" "$tmp/old.h5"
/usr/bin/python3 "$(dirname "$0")/python.py" "$tmp/old.h5" 2
