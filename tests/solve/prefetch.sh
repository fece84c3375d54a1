#!/bin/sh
# The bond loop's prefetches (solve/bonds.c, bonds_prefetch) change the
# speed and nothing else: runs with them (DEM_PREFETCH=on), without (off)
# and with the engine's timed choice between the two (bonds_tune_prefetch,
# a trial of windows of each within these steps) are the same to the bit;
# another value is an error.
# With OBJDUMP, also that they are in the machine code: a compiler may
# drop a function of prefetches alone as one without effects, which only
# the machine code tells; every version of bonds_share (one for each kind
# of CPU, solve/clones.h) must hold some (x86-64). A version's cold part
# (GCC's .cold, its rarely taken branches) is not a version.
# Usage: prefetch.sh BIN_DIR TMP_DIR [OBJDUMP]
set -eu
bin=$1 tmp=$2 objdump=${3:-}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$tmp"
mkdir -p "$tmp"
if [ -n "$objdump" ]; then
	"$objdump" -d --no-show-raw-insn "$bin/solve" | awk '
		/^[0-9a-f]+ <bonds_share[.>]/ && !/resolver/ && !/\.cold>/ {
			f = substr($2, 2, length($2) - 3)
			n[f] = 0
			next
		}
		/^[0-9a-f]+ </ { f = "" }
		f != "" && /prefetch/ { n[f]++ }
		END {
			bad = 0
			for (f in n) {
				printf "%s: %d prefetches\n", f, n[f]
				if (n[f] == 0)
					bad = 1
			}
			if (length(n) == 0) {
				print "no bonds_share in the program"
				bad = 1
			}
			exit bad
		}'
fi
. "$here/case.sh"
lattice 1500
case_file "$tmp/c.json" '"stop": {"steps": 300}' 40 2e6
for m in on off; do
	DEM_PREFETCH=$m "$bin/solve" --quiet --threads 1 --output "$tmp/$m.h5" "$tmp/c.json"
done
"$bin/solve" --quiet --threads 2 --report "$tmp/timed.json" --output "$tmp/timed.h5" "$tmp/c.json"
grep -q '"bond_prefetch"' "$tmp/timed.json"
/usr/bin/python3 "$here/same_run.py" "$tmp/on.h5" "$tmp/off.h5"
/usr/bin/python3 "$here/same_run.py" "$tmp/on.h5" "$tmp/timed.h5"
# Any other value is refused with a message naming it, before any output.
if DEM_PREFETCH=yes "$bin/solve" --quiet --output "$tmp/bad.h5" "$tmp/c.json" 2>"$tmp/bad.err"; then
	echo "DEM_PREFETCH=yes was accepted"
	exit 1
fi
grep -q 'DEM_PREFETCH=yes: expected on or off' "$tmp/bad.err"
test ! -e "$tmp/bad.h5"
echo "the same runs with the prefetches, without and timed"
