#!/bin/sh
# The engine's versions for each kind of CPU (solve/clones.h) give the same
# run to the bit: each law's run natively (on a CPU with AVX-512 the
# x86-64-v4 versions, on AMD's the 512-bit ones) and under valgrind, whose
# simulated CPU has AVX2 and not AVX-512, so the AVX2 versions run.
# Usage: cpu_versions.sh BIN_DIR TMP_DIR VALGRIND
set -eu
bin=$1 tmp=$2 valgrind=$3
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
rm -rf "$tmp"
mkdir -p "$tmp"
. "$here/case.sh"
lattice 1500
for m in linear cement concrete-jcfpm concrete-exponential; do
	if [ $m = linear ]; then
		case_file "$tmp/$m.json" '"stop": {"steps": 60}' 40 2e6
	else
		cat > "$tmp/$m.json" <<JSON
{"assembly": "$tmp/a.h5", "material": "$root/share/materials/$m.json",
 "loading": [{"axial": {"mode": "strain_rate", "rate": 40}}], "stop": {"steps": 60}}
JSON
	fi
	"$bin/solve" --quiet --threads 1 --output "$tmp/$m-native.h5" "$tmp/$m.json"
	"$valgrind" --tool=none --error-exitcode=9 -q "$bin/solve" --quiet --threads 1 \
		--output "$tmp/$m-avx2.h5" "$tmp/$m.json"
	/usr/bin/python3 "$here/same_run.py" "$tmp/$m-native.h5" "$tmp/$m-avx2.h5"
done
